// Seed references written for a reader (common/seed_citation.hpp).
#include "common/seed_citation.hpp"

#include <gtest/gtest.h>

using rtsim::cite_seeds;
using rtsim::cited_seeds;

TEST(SeedCitation, SeedLinesBecomeAuthorYearAndLines) {
  EXPECT_EQ(cite_seeds("seed 000 L584"), "Ullner 1983, line 584");
  EXPECT_EQ(cite_seeds("seed 001 L883, L961"), "Gaudet 1985, lines 883, 961");
  EXPECT_EQ(cite_seeds("seed 000 L572-L588 (Fig. 2-17: 17 operations deep)"),
            "Ullner 1983, lines 572-588 (Fig. 2-17: 17 operations deep)");
  EXPECT_EQ(cite_seeds("seed 000 L723 and L2084-L2108: about 5 us"),
            "Ullner 1983, line 723 and lines 2084-2108: about 5 us");
  EXPECT_EQ(cite_seeds("seed 001 L951 (5 MHz SJ16), L859 (Weitek FPU)"),
            "Gaudet 1985, line 951 (5 MHz SJ16), line 859 (Weitek FPU)");
  EXPECT_EQ(cite_seeds("assumption: one bus word time (L883); seed 004 L120"),
            "assumption: one bus word time (L883); Interactive 3D Graphics 1995, line 120");
  EXPECT_EQ(cite_seeds("seed 002 §3"), "Wang, Lewis & Hung c. 2000 §3");
  EXPECT_EQ(cite_seeds("seed 000 L762; XL5 and L9X stay"),
            "Ullner 1983, line 762; XL5 and L9X stay");
  // Not a seed this project has, or not a seed reference at all: as it was.
  EXPECT_EQ(cite_seeds("seed 003 L5"), "seed 003 L5");
  EXPECT_EQ(cite_seeds("seed 0001 L5"), "seed 0001 L5");
  EXPECT_EQ(cite_seeds("random seed 1985"), "random seed 1985");
  EXPECT_EQ(cite_seeds(""), "");
}

TEST(SeedCitation, CitedSeedsAreListedOnceInOrder) {
  EXPECT_EQ(cited_seeds("seed 001 L959; seed 000 L476 and seed 001 L962"),
            (std::vector<std::string>{"001", "000"}));
  EXPECT_TRUE(cited_seeds("seed 003 L5, seed 0001, random seed 1985, seed 00").empty());
}

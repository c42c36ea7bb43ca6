#include "platform/machines/ullner_scanline_tree/pixel_converter_node.hpp"

#include <algorithm>

#include "platform/machines/machine_run.hpp"
#include "platform/machines/ullner_scanline_tree/frame_sequencer.hpp"

namespace rtsim::platform::ullner_scanline_tree {

namespace {
const modules::TimeParam kPixelTime(
    {.name = "pixel_time",
     .default_value = "127 ns",
     .description = "time to put out one pixel of a segment (its colour registers step once)",
     .source = "derived: the seed gives none; a 512-pixel line in the 65 us a line has at 30 "
               "frames a second and 512 lines (seed 000 L1551), 127 ns a pixel"});
const modules::FlagParam kPaced(
    {.name = "paced",
     .default_value = "true",
     .description = "paint as the video beam passes (30 frames a second); false: as fast as the "
                    "pixel time allows, to measure what the tree delivers",
     .source = "seed 000 L1521-L1525: the processor keeps up with the beam"});
const modules::FrequencyParam kFrameRate(
    {.name = "frame_rate",
     .default_value = "30 Hz",
     .description = "video frames a second: a line's time is a frame's over the lines",
     .source = "seed 000 L959, L1551"});
const modules::CountParam kStripLinesAhead(
    {.name = "strip_lines_ahead",
     .default_value = "1",
     .min = "0",
     .max = "4094",
     .unit = "lines",
     .description = "a split root's strips: lines a strip's processor may paint before the beam "
                    "reaches them (the composing hardware's line buffers); unsplit, the one "
                    "processor paints as the beam passes",
     .source = "assumption: \"some faster hardware must still be included to compose the "
               "resulting bands of pixels into the continuous stream\" (seed 000 L1629): it "
               "holds a line of each strip, so a strip is painted during the line before"});
const modules::CountParam kQueueDepth(
    {.name = "queue_depth",
     .default_value = "2",
     .min = "1",
     .max = "4096",
     .unit = "segments",
     .description = "segments its input queue holds",
     .source = "assumption: the merging processors' short queues (seed 000 L1519)"});
}  // namespace

const modules::FrequencyParam& PixelConverterNode::frame_rate() { return kFrameRate; }

void PixelConverterNode::declare_params(const modules::ParamDecls& pcp) {
  pcp.add(kPixelTime);
  pcp.add(kPaced);
  pcp.add(kFrameRate);
  pcp.add(kQueueDepth);
  pcp.add(kStripLinesAhead);
}

PixelConverterNode::PixelConverterNode(sc_core::sc_module_name name, MachineRun& run,
                                       const FrameSequencer& frames,
                                       std::vector<scanline::PixelRow>& rows,
                                       const scanline::Strip& strip, std::vector<RootFault> faults,
                                       const ProbeStages& stages)
    : modules::Processor(name, run.trace()),
      in("in", modules::ModuleParams(run.registry(), kName).get(kQueueDepth)),
      params_(run.registry(), kName),
      run_(run),
      frames_(frames),
      rows_(rows),
      strip_(strip),
      faults_(std::move(faults)),
      probe_(run.probe()),
      stages_(stages),
      paced_(params_.get(kPaced)),
      // Read (and checked) unsplit too, where no strip paints ahead.
      ahead_(params_.get(kStripLinesAhead) * (strip.levels > 0 ? 1 : 0)),
      pixel_time_(params_.get(kPixelTime)),
      line_time_(
          sc_core::sc_time(1.0 / (params_.get(kFrameRate).hz * run.height()), sc_core::SC_SEC)) {
  SC_THREAD(run);
}

void PixelConverterNode::run() {
  const int width = run_.width(), height = run_.height();
  for (;;) {
    const sc_core::sc_time since = clock_.now();
    modules::wait_for_item(in.fifo, clock_);
    sc_core::sc_time taken;
    SegmentMessage m = in.fifo.get(clock_.now(), taken);
    clock_.catch_up(taken);
    waited_since(since, Wait::kData);
    if (!open_) {
      // A frame's first message: its beam starts at the frame's start (L1551).
      const std::size_t f = per_line_.size();
      begin_ = frames_.frame_start(f);
      per_line_.emplace_back(static_cast<std::size_t>(height), 0);
      line_late_.emplace_back(static_cast<std::size_t>(height), 0);
      open_ = true;
      if (f > 0) clear_strip();
    }
    // A line mark of a split root's network (firmware/scanline/splitting.hpp): no pixels.
    if (m.segment.mark) continue;
    // A word corrupted on the way in (--fault root:WORD:XOR), 12 bits of it.
    const std::uint64_t first_word = words_seen_;
    words_seen_ += scanline::kSegmentWords;
    for (RootFault& f : faults_) {
      if (f.applied || f.word < first_word || f.word >= words_seen_) continue;
      auto w = m.segment.words();
      auto& word = w[static_cast<std::size_t>(f.word - first_word)];
      word = static_cast<std::int16_t>((word ^ f.xor_mask) & scanline::kWordMax);
      m.segment = scanline::Segment::from_words(w, m.segment.polygon);
      f.applied = true;
    }
    const scanline::Segment& s = m.segment;
    probe_.add(s.journey, stages_.pcp_in, modules::LatencyPart::kQueueing,
               clock_.now() - m.arrived);
    if (s.dummy()) {
      open_ = false;
      frame_end_ = clock_.now();
      if (paced_)
        frame_end_ = std::max(frame_end_, begin_ + line_time_ * static_cast<double>(height));
      clock_.sync();
      continue;
    }
    if (s.y >= height) {
      probe_.drop(s.journey);
      continue;
    }
    const auto [first, end] = scanline::covered_pixels(s, width, strip_);
    const auto line = static_cast<std::size_t>(s.y);
    ++per_line_.back()[line];
    if (paced_) {
      // The beam reaches the segment's first pixel at T0 + y t_line + first t_line / width.
      const sc_core::sc_time beam =
          begin_ + line_time_ * (static_cast<double>(s.y) +
                                 static_cast<double>(first) / static_cast<double>(width));
      // A strip's processor may paint up to `ahead_` lines before the beam, into the line
      // buffers of the hardware composing the strips.
      const double ahead = static_cast<double>(ahead_);
      const sc_core::sc_time from =
          beam > line_time_ * ahead ? beam - line_time_ * ahead : sc_core::SC_ZERO_TIME;
      if (clock_.now() > beam) {
        ++late_;
        lateness_ += clock_.now() - beam;
        line_late_.back()[line] = 1;
      } else if (from > clock_.now()) {
        // The beam (or the line buffer) has not reached it yet.
        probe_.add(s.journey, stages_.pcp, modules::LatencyPart::kQueueing, from - clock_.now());
        idle_until(from, Wait::kData);
      }
    }
    const sc_core::sc_time painting = clock_.now();
    if (end > first)
      compute_for(pixel_time_ * static_cast<double>(end - first), "paint", {{"y", s.y}});
    probe_.add(s.journey, stages_.pcp, modules::LatencyPart::kService, clock_.now() - painting);
    probe_.end(s.journey, clock_.now());
    scanline::paint(s, width, rows_[line], strip_);
    ++segments_;
    pixels_ += static_cast<std::uint64_t>(end - first);
  }
}

void PixelConverterNode::clear_strip() {
  const auto [first, end] = scanline::strip_pixels(run_.width(), strip_);
  for (scanline::PixelRow& row : rows_)
    scanline::blank_pixels(row, first, end, run_.scene().background);
}

}  // namespace rtsim::platform::ullner_scanline_tree

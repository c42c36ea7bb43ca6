#include "platform/machines/ullner_hidden_line/divider_node.hpp"

#include <algorithm>

#include "modules/sim_time.hpp"
#include "platform/machines/ullner_hidden_line/pipe_stage.hpp"

namespace rtsim::platform::ullner_hidden_line {

namespace {
const modules::TimeParam kDivisionTime(
    {.name = "division_time",
     .default_value = "8 us",
     .description = "time of one division t = t_n / t_d (a hidden part's end); the point's "
                    "coordinates follow from t as the display draws",
     .source = "assumption: the seed gives the divider no time (L1765); a serial divider "
               "producing a bit of the quotient a bit time, 16 bits at 500 ns, as fast as the "
               "links deliver intersections"});
}  // namespace

void DividerNode::declare_params(const modules::ParamDecls& divider) { divider.add(kDivisionTime); }

DividerNode::DividerNode(sc_core::sc_module_name name, const params::ParamRegistry& registry)
    : sc_core::sc_module(name),
      modules::StatGroup(this->name()),
      in("in"),
      division_time_(modules::ModuleParams(registry, kName).get(kDivisionTime)) {
  in.register_b_transport(this, &DividerNode::b_transport);
}

void DividerNode::b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay) {
  (void)delay;  // the time travels in the message
  const MessageInFlight* f = carried(gp);
  if (!f) {
    gp.set_response_status(tlm::TLM_GENERIC_ERROR_RESPONSE);
    return;
  }
  const sc_core::sc_time accepted = std::max(f->at, done_);
  accepted_ = accepted;
  done_ = accepted;
  const hiddenline::Message& m = f->message;
  received_.push_back(m);
  switch (m.kind) {
    case hiddenline::Message::Kind::kSegment:
      ++segments_;
      segment_arrivals_.emplace_back(m.segment.edge, f->at);
      break;
    case hiddenline::Message::Kind::kIntersection:
      if (m.intersection.h) {
        ++marked_;
        busy_.record(accepted, division_time_);
        done_ = modules::plus(accepted, division_time_);
      } else {
        ++unmarked_;
      }
      break;
    case hiddenline::Message::Kind::kEnd:
      ended_ = true;
      finished_ = done_;
      break;
  }
  gp.set_response_status(tlm::TLM_OK_RESPONSE);
}

}  // namespace rtsim::platform::ullner_hidden_line

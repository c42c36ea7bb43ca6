#include "platform/machines/sort_first/mesh_channel.hpp"

#include "modules/sim_time.hpp"

namespace rtsim::platform::sort_first {

void MeshChannel::declare_params(const modules::ParamDecls& machine) {
  modules::Link::declare_params(
      machine.sub(kLinkClass),
      {.latency = "100 ns",
       .lanes = "16",
       .bit_rate = "87.5 Mbit/s",
       .bit_time = "",
       .source = "assumption: a 1995 multicomputer's mesh channel (16 bits wide, 175 Mbyte/s, as "
                 "the Intel Paragon's), 100 ns a router; the seed names no network (L503)"});
  modules::Link::declare_params(
      machine.sub(kHostBus),
      {.latency = "0 s",
       .lanes = "32",
       .bit_rate = "25 Mbit/s",
       .bit_time = "",
       .source = "assumption: a 32-bit frame-buffer bus at 25 MHz (100 Mbyte/s, HIPPI's order); "
                 "the seed says only that finished pixels go to the frame buffer (L505)"});
}

void MeshChannel::check_params(const params::ParamRegistry& registry) {
  modules::Link::check_params(modules::ModuleParams(registry, kLinkClass));
  modules::Link::check_params(modules::ModuleParams(registry, kHostBus));
}

MeshChannel::MeshChannel(sc_core::sc_module_name name, int side,
                         const params::ParamRegistry& registry)
    : sc_core::sc_module(name),
      topology_(side, side, false, false),
      host_(static_cast<std::size_t>(side) * static_cast<std::size_t>(side)) {
  const modules::ModuleParams link(registry, kLinkClass);
  for (int n = 0; n < topology_.nodes(); ++n)
    for (const modules::Direction d : modules::kDirections) {
      const bool wired = topology_.neighbour(topology_.node(n), d).has_value();
      links_.push_back(
          wired ? std::make_unique<modules::Link>(std::string(kLinkClass) + std::to_string(n) +
                                                      "." + std::string(modules::direction_name(d)),
                                                  link)
                : nullptr);
    }
  host_bus_ = std::make_unique<modules::Link>(kHostBus, modules::ModuleParams(registry, kHostBus));
  for (std::size_t k = 0; k <= host_; ++k)
    out_.push_back(std::make_unique<tlm_utils::simple_initiator_socket<MeshChannel>>(
        ("to_node" + std::to_string(k)).c_str()));
  SC_THREAD(run);
}

void MeshChannel::attach(std::size_t node, modules::MessageQueue<Message>& inbox) {
  out_.at(node)->bind(inbox.socket);
  const std::string queue = inbox.name();
  modules::connect(name(), queue.substr(0, queue.rfind('.')), "delivers to");
}

void MeshChannel::push(const sc_core::sc_time& at, std::uint64_t id, std::size_t node) {
  hops_queue_.push({at, next_seq_++, id, node});
}

void MeshChannel::send(std::size_t from, std::size_t to, Message msg, std::uint64_t bytes,
                       const sc_core::sc_time& ready) {
  const std::uint64_t id = next_id_++;
  pending_.emplace(id, Pending{std::move(msg), to, 8 * bytes});
  push(ready, id, from);
  put_event_.notify(sc_core::SC_ZERO_TIME);
}

void MeshChannel::run() {
  for (;;) {
    if (hops_queue_.empty()) {
      sc_core::wait(put_event_);
      continue;
    }
    const Hop h = hops_queue_.top();
    const sc_core::sc_time now = modules::sim_now();
    if (h.at > now) {
      // A message handed over meanwhile may be due sooner.
      sc_core::wait(h.at - now, put_event_);
      continue;
    }
    hops_queue_.pop();
    auto it = pending_.find(h.id);
    Pending& p = it->second;
    if (h.node == p.to) {
      Message m = std::move(p.message);
      const std::uint64_t bits = p.bits;
      pending_.erase(it);
      modules::send_message(*out_[h.node], m, h.at, bits);
      continue;
    }
    if (h.node == host_ || p.to == host_) {
      // The host bus: one transfer between the host and any renderer.
      push(host_bus_->transfer(p.bits, h.at), h.id, h.node == host_ ? p.to : host_);
      continue;
    }
    const modules::GridNode at = topology_.node(static_cast<int>(h.node));
    const modules::Direction d = topology_.next_hop(at, topology_.node(static_cast<int>(p.to)));
    modules::Link& link = *links_[h.node * 4 + static_cast<std::size_t>(d)];
    const modules::GridNode next = *topology_.neighbour(at, d);
    push(link.transfer(p.bits, h.at), h.id, static_cast<std::size_t>(topology_.index(next)));
  }
}

}  // namespace rtsim::platform::sort_first

#include "simnet/path.hpp"

namespace arena::simnet {

namespace {

std::variant<stream_link, datagram_link> make_link(link_kind kind, const conditions& c, std::uint64_t seed) {
    if (kind == link_kind::stream) return stream_link(c, seed);
    return datagram_link(c, seed);
}

}  // namespace

path::path(link_kind kind, const conditions& c, std::uint64_t seed) : kind_(kind), link_(make_link(kind, c, seed)) {}

void path::send(std::span<const std::uint8_t> frame, bool reliable, sim_time now) {
    if (closed_) return;
    if (auto* s = std::get_if<stream_link>(&link_)) return s->write(frame, now);
    auto& d = std::get<datagram_link>(link_);
    if (reliable) {
        d.send_reliable(frame, now);
    } else {
        d.send(frame, now);
    }
}

void path::close(sim_time now) {
    if (closed_) return;
    closed_ = true;
    if (auto* s = std::get_if<stream_link>(&link_)) return s->close(now);
    std::get<datagram_link>(link_).send_reliable({}, now);
}

std::optional<sim_time> path::next_due() const {
    return std::visit([](const auto& link) { return link.next_due(); }, link_);
}

const link_stats& path::stats() const {
    return std::visit([](const auto& link) -> const link_stats& { return link.stats(); }, link_);
}

}  // namespace arena::simnet

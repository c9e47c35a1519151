#pragma once
// Graph colouring of the contacts for the wide solve (Box2D v3's constraint graph, our code):
// contacts of one colour share no moving body, so `wide_lanes` of them are solved at once with
// nothing to order between them, and solving colour after colour is a Gauss-Seidel sweep like
// the one-at-a-time solver's, in a different order.
//
// Greedy and in contact order: each contact takes the lowest colour neither of its moving
// bodies has yet (static bodies and walls, slot 0, never count: nothing they touch moves
// them). A contact for which no colour is left (a body touching more than `colour_count`
// others) goes to the overflow and is solved alone, after the colours. Nothing here depends on
// the lane width or the target, so neither do the results.
#include <cstdint>
#include <span>
#include <vector>

#include "server/world/contacts.hpp"

namespace arena::world {

class contact_colouring {
public:
    // Box2D v3 uses 24; a pyramid of boxes needs about 8.
    static constexpr uint32_t colour_count = 24;
    // Marks a lane that holds no contact.
    static constexpr uint32_t no_contact = UINT32_MAX;

    // Colours `contacts` (their slots set by solver_slots::gather, slot_count slots) and lays
    // them out in groups of wide_lanes: each colour's contacts in contact order, its last group
    // padded with no_contact, then one group per overflow contact.
    void colour(std::span<const contact> contacts, size_t slot_count);

    // Group g's lanes are lanes()[g·wide_lanes ...]; each a contact index or no_contact.
    std::span<const uint32_t> lanes() const { return lanes_; }
    size_t group_count() const;
    // Colours used, without the overflow (tests and the profile).
    uint32_t colours_used() const { return colours_used_; }
    size_t overflow() const { return overflow_; }

private:
    std::vector<uint32_t> used_;      // slot → bit c set when one of its contacts has colour c
    std::vector<uint8_t> colour_of_;  // contact → colour, colour_count for the overflow
    std::vector<uint32_t> lanes_;
    uint32_t colours_used_ = 0;
    size_t overflow_ = 0;
};

}  // namespace arena::world

#pragma once
// The data cards of the keywords that make bodies interact: *CONTACT_... and *RIGIDWALL_PLANAR,
// read into their Deck records (deck.h). The keyword block, its ID card and the record's creation
// stay with the parser (deck_parser.cpp); these read one data card each, checking every field.
#include <string>
#include <vector>

#include "solver/deck/card.h"
#include "solver/deck/deck.h"

namespace crashlink::deck {

/// Data card `index` (0: card 1; the ID card not counted) of a *CONTACT_ keyword into `k`; notes
/// for the user (optional cards D and later are read without effect) go to `notes`.
void read_contact_card(const Card& c, int index, ContactCard& k, std::vector<std::string>& notes);

/// Data card `index` (0 or 1; the ID card not counted) of *RIGIDWALL_PLANAR into `w`.
void read_rigid_wall_card(const Card& c, int index, RigidWallCard& w);

}  // namespace crashlink::deck

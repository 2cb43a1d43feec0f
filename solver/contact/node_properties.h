#pragma once
// What a contact needs to know of every node of the model, computed once at set-up
// (node_properties, which carries the formulas): offset, stiffness and mass per node.
#include <vector>

#include "solver/model/model.h"

namespace crashlink::contact {

struct NodeProperties {
  std::vector<double> half_thickness_m;  ///< [n]
  std::vector<double> stiffness_N_m;     ///< [n]
  std::vector<double> mass_kg;           ///< [n]
  std::vector<double> unfixed_mass_kg;   ///< [n] mass_kg before fixed nodes become infinite
};

/// For contact c (penalty scale, master parts, slave nodes); `mass` [n] the solver's lumped
/// masses, used for rigid bodies without a given mass (may be null). Per node:
///   half_thickness_m  half the thickness of the thickest shell around the node (0: solids only),
///                     the node's offset from its mid-surface;
///   stiffness_N_m     the segment-based (LS-DYNA SOFT=0) stiffness of the node's own elements,
///                     the largest of shells s K A / max diagonal and hex faces s K A_mean^2 / V
///                     around it; 0 for nodes of rigid parts;
///   mass_kg           the mass that resists a contact force on the node: the lumped shares
///                     (hex rho V / 8, shell rho t A / 4) of the contact's elements on it, a
///                     rigid body's whole mass for its nodes, infinity for a node fixed in x, y, z.
NodeProperties node_properties(const model::Model& m, const model::Contact& c, const double* mass);

/// Reduced mass a b / (a + b) of two masses in series, an infinite one leaving the other [kg].
double reduced_mass(double a, double b);

}  // namespace crashlink::contact

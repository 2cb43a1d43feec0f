#pragma once
// Master segments of a contact interface and the penalty stiffness of each (set-up, once):
// shell elements and exterior hexahedron faces of the master parts (build_segments), the slave
// faces of a two-pass contact (slave_faces, build_faces). Stiffness: Hallquist, LS-DYNA Theory
// Manual, "Penalty method" (SOFT = 0), on solid_face_stiffness and shell_stiffness.
#include <cstdint>
#include <vector>

#include "solver/model/model.h"

namespace crashlink::contact {

/// Structure of arrays, s = segment count.
struct SegmentSet {
  std::vector<std::int32_t> nodes;  ///< [4s] node indices, triangle: nodes[4i+3] == nodes[4i+2]
  /// [s] master thickness offset (t/2 for shells, 0 for solid faces) [m]
  std::vector<double> offset_m;
  /// [s] one-sided faces: deepest penetration still treated as contact (half the element's
  /// thickness V/A) [m]; shells: 0 (two-sided: contact_pass.cpp classify)
  std::vector<double> depth_m;
  /// [s] penalty stiffness of a slave node on the segment (LS-DYNA SOFT=0) [N/m]; 0 for segments
  /// of rigid parts (the slave side's stiffness is used instead)
  std::vector<double> stiffness_N_m;
  /// [s] what stiffness_N_m would be with the rigid material's own moduli (used if both sides
  /// are rigid)
  std::vector<double> rigid_stiffness_N_m;
  std::vector<std::uint8_t> two_sided;  ///< [s] 1 for shells
  std::vector<std::uint8_t> rigid;      ///< [s] 1 if the segment belongs to a rigid part

  std::size_t size() const { return offset_m.size(); }
  bool triangle(std::size_t i) const { return nodes[4 * i + 3] == nodes[4 * i + 2]; }
};

/// Penalty stiffness, Hallquist, LS-DYNA Theory Manual, "Penalty method" (SOFT = 0):
///   solid face:  k = s K A^2 / V      (K bulk modulus, A face area, V element volume)
///   shell:       k = s K A / max(shell diagonal)   (triangle: the longest edge)
double solid_face_stiffness(double s, double K, double A, double V);
double shell_stiffness(double s, double K, double A, double max_diagonal);

/// Volume of a Hex8 (six tetrahedra around the 0-6 diagonal) at coordinates x [3n].
double hex_volume(const double* x, const std::int32_t* conn);
/// Area of a quad (0.5 |d1 x d2|, exact for a flat quad) or triangle; `q` 4 node indices.
double segment_area(const double* x, const std::int32_t* q);
/// Longest diagonal of a quad, longest edge of a triangle.
double segment_max_diagonal(const double* x, const std::int32_t* q);

/// Segments of `master_parts` at the reference coordinates:
///   Shell4 parts: every element, a quad or a triangle (n3 == n2); two-sided, offset t/2 on
///                 whichever side the slave node is;
///   Hex8 parts:   the exterior faces (faces used by exactly one Hex8 element of the whole
///                 model), nodes ordered so that the normal points out of the element; one-sided,
///                 offset 0, depth V / (2 A).
/// Throws ModelError if a part index is out of range or the parts give no segment.
SegmentSet build_segments(const model::Model& m, const std::vector<int>& master_parts,
                          double penalty_scale);

/// The slave surface of a two-pass contact, outward, 4 node indices per face in model order:
/// shell elements with all four nodes in the set; exterior hexahedron faces (used by one Hex8 of
/// the model) with all four nodes in the set; and the other exterior faces of those faces'
/// hexahedra with at least one node in the set and none on a master part's element (the side
/// faces along the slave face's edges, so that a tilted face's edge meets a surface; faces glued
/// to the master side, and parts merely glued to the slave part, stay out).
std::vector<std::int32_t> slave_faces(const model::Model& m, const std::vector<std::int32_t>& nodes,
                                      const std::vector<int>& master_parts);

/// Segments for explicit faces (4 node indices each, as slave_faces gives them), with the
/// offset, depth and stiffness of the element each face belongs to. Throws ModelError if a face
/// belongs to no element.
SegmentSet build_faces(const model::Model& m, const std::vector<std::int32_t>& faces,
                       double penalty_scale);

/// Outward faces of a Hex8 in LS-DYNA order (bottom, top, then the four sides).
inline constexpr int kHexFaces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                        {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};

}  // namespace crashlink::contact

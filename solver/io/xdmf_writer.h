#pragma once
// result.xdmf: an XDMF 3 description of the field states in result.h5 for ParaView (Xdmf3 reader)
// and VisIt. Light data only; every array is a reference "result.h5:/path" into the HDF5 file.
//
// Structure: a temporal collection with one spatial collection per state; in it one uniform grid
// per part (topology Hexahedron [ne,8] or Quadrilateral [ne,4], indices into the model's full node
// array), geometry = the state's current coordinates x0 + u [n,3] (written per state by the result
// writer: simplest form every reader opens), node attributes displacement and velocity, cell
// attributes eps_p, von_mises and stress (6 Voigt components xx,yy,zz,xy,yz,zx, as a Matrix
// named stress_xx_yy_zz_xy_yz_zx) when the state has them. Without states the
// file holds the reference mesh only.
#include <cstddef>
#include <string>
#include <vector>

namespace crashlink::io {

struct XdmfPart {
  std::string name;
  bool hexahedron = true;  ///< false: Quadrilateral (Shell4; a triangle repeats node 2)
  std::size_t element_count = 0;
  std::string connectivity;  ///< HDF5 path of the [ne, 8|4] int32 node indices (0-based)
};

struct XdmfPartFields {
  std::string eps_p;      ///< HDF5 path of [ne] doubles, "" if absent
  std::string von_mises;  ///< HDF5 path of [ne] doubles, "" if absent
  std::string stress;     ///< HDF5 path of [ne, 6] doubles, "" if absent
};

struct XdmfState {
  double time_s = 0.0;
  std::string coordinates;            ///< HDF5 path of the current coordinates [n,3]
  std::string displacement;           ///< [n,3], "" if absent
  std::string velocity;               ///< [n,3], "" if absent
  std::vector<XdmfPartFields> parts;  ///< one per XdmfDocument::parts, or empty
};

struct XdmfDocument {
  std::string h5_file = "result.h5";  ///< as referenced from the xdmf file (relative name)
  std::size_t node_count = 0;
  std::string reference_coordinates;  ///< HDF5 path of x0 [n,3] (used when there is no state)
  std::vector<XdmfPart> parts;
  std::vector<XdmfState> states;
};

/// The XML text of the document.
std::string xdmf_text(const XdmfDocument& doc);

/// Writes the document to `path` atomically (a temporary beside it, then rename), so a reader or
/// a crash never sees a half-written file. Throws ResultFileError on failure.
void write_xdmf(const std::string& path, const XdmfDocument& doc);

}  // namespace crashlink::io

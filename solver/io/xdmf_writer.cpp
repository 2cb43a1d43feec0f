#include "solver/io/xdmf_writer.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "solver/io/hdf5_handles.h"

namespace crashlink::io {

namespace {

/// Escapes the five XML special characters (part names are user text).
std::string xml_escape(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (const char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

void data_item(std::string& out, const XdmfDocument& doc, const std::string& dims,
               const char* number_type, int precision, const std::string& path,
               const std::string& indent) {
  out += fmt::format(
      "{}<DataItem Dimensions=\"{}\" NumberType=\"{}\" Precision=\"{}\" Format=\"HDF\">{}:{}"
      "</DataItem>\n",
      indent, dims, number_type, precision, xml_escape(doc.h5_file), xml_escape(path));
}

void attribute(std::string& out, const XdmfDocument& doc, const std::string& pad, const char* name,
               const char* type, const char* center, const std::string& dims,
               const std::string& path) {
  if (path.empty()) return;
  out += fmt::format("{}<Attribute Name=\"{}\" AttributeType=\"{}\" Center=\"{}\">\n", pad, name,
                     type, center);
  data_item(out, doc, dims, "Float", 8, path, pad + "  ");
  out += pad + "</Attribute>\n";
}

/// One uniform grid, indented by `pad`: part `p` at the given geometry, with the state's
/// attributes if any.
void part_grid(std::string& out, const XdmfDocument& doc, const std::string& pad, std::size_t p,
               const std::string& coordinates, const XdmfState* state) {
  const std::string in = pad + "  ";
  const XdmfPart& part = doc.parts[p];
  const std::size_t ne = part.element_count;
  const int k = part.hexahedron ? 8 : 4;
  out += fmt::format("{}<Grid Name=\"{}\" GridType=\"Uniform\">\n", pad, xml_escape(part.name));
  if (state != nullptr) out += fmt::format("{}<Time Value=\"{}\"/>\n", in, state->time_s);
  out += fmt::format(
      "{}<Topology TopologyType=\"{}\" NumberOfElements=\"{}\" NodesPerElement=\"{}\">\n", in,
      part.hexahedron ? "Hexahedron" : "Quadrilateral", ne, k);
  data_item(out, doc, fmt::format("{} {}", ne, k), "Int", 4, part.connectivity, in + "  ");
  out += in + "</Topology>\n";
  out += in + "<Geometry GeometryType=\"XYZ\">\n";
  data_item(out, doc, fmt::format("{} 3", doc.node_count), "Float", 8, coordinates, in + "  ");
  out += in + "</Geometry>\n";
  if (state != nullptr) {
    const std::string nodal = fmt::format("{} 3", doc.node_count);
    attribute(out, doc, in, "displacement", "Vector", "Node", nodal, state->displacement);
    attribute(out, doc, in, "velocity", "Vector", "Node", nodal, state->velocity);
    if (p < state->parts.size()) {
      const XdmfPartFields& f = state->parts[p];
      attribute(out, doc, in, "eps_p", "Scalar", "Cell", fmt::format("{}", ne), f.eps_p);
      attribute(out, doc, in, "von_mises", "Scalar", "Cell", fmt::format("{}", ne), f.von_mises);
      // Not Tensor6: XDMF orders that xx,xy,xz,yy,yz,zz; ours is Voigt, named in the array name.
      attribute(out, doc, in, "stress_xx_yy_zz_xy_yz_zx", "Matrix", "Cell", fmt::format("{} 6", ne),
                f.stress);
    }
  }
  out += pad + "</Grid>\n";
}

}  // namespace

std::string xdmf_text(const XdmfDocument& doc) {
  std::string out;
  out += "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n";
  out += "<Xdmf Version=\"3.0\" xmlns:xi=\"http://www.w3.org/2001/XInclude\">\n";
  out += "  <Domain>\n";
  if (doc.states.empty()) {
    out += "    <Grid Name=\"mesh\" GridType=\"Collection\" CollectionType=\"Spatial\">\n";
    for (std::size_t p = 0; p < doc.parts.size(); ++p) {
      part_grid(out, doc, "      ", p, doc.reference_coordinates, nullptr);
    }
    out += "    </Grid>\n";
  } else {
    out += "    <Grid Name=\"states\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (std::size_t s = 0; s < doc.states.size(); ++s) {
      const XdmfState& state = doc.states[s];
      out += fmt::format(
          "      <Grid Name=\"state_{}\" GridType=\"Collection\" CollectionType=\"Spatial\">\n", s);
      out += fmt::format("        <Time Value=\"{}\"/>\n", state.time_s);
      for (std::size_t p = 0; p < doc.parts.size(); ++p) {
        part_grid(out, doc, "        ", p, state.coordinates, &state);
      }
      out += "      </Grid>\n";
    }
    out += "    </Grid>\n";
  }
  out += "  </Domain>\n";
  out += "</Xdmf>\n";
  return out;
}

void write_xdmf(const std::string& path, const XdmfDocument& doc) {
  const std::string text = xdmf_text(doc);
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) {
      throw ResultFileError(tmp, "/",
                            fmt::format("cannot create the XDMF file: {}; check the "
                                        "output directory is writable",
                                        std::strerror(errno)));
    }
    f.write(text.data(), static_cast<std::streamsize>(text.size()));
    f.flush();
    if (!f) {
      const int err = errno;
      f.close();
      std::remove(tmp.c_str());  // the XDMF file before it stays as it was
      throw ResultFileError(
          tmp, "/", fmt::format("cannot write the XDMF file: {} (disk full?)", std::strerror(err)));
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    throw ResultFileError(path, "/",
                          fmt::format("cannot rename {} to it: {}", tmp, std::strerror(errno)));
  }
}

}  // namespace crashlink::io

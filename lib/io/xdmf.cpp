#include "io/xdmf.hpp"

#include "io/atomic_file.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>

#include "core/error.hpp"
#include "io/header.hpp"
#include "io/mesh_io.hpp"
#include "io/provenance_text.hpp"

namespace frac::io {
namespace {

// Shape and number type of a dataset, as XDMF names them.
struct Shape {
  std::vector<hsize_t> dims;
  std::string number_type;  // Float, Int, UInt, Char, UChar
  std::size_t precision = 8;
};

std::optional<Shape> dataset_shape(const Group& g, const std::string& name) {
  if (!g.has(name)) return std::nullopt;
  Hid d(H5Oopen(g.id(), name.c_str(), H5P_DEFAULT));
  if (d.get() < 0 || H5Iget_type(d.get()) != H5I_DATASET) return std::nullopt;
  Hid type(H5Dget_type(d.get()));
  Hid space(H5Dget_space(d.get()));
  Shape s;
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) return std::nullopt;
  s.dims.resize(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space.get(), s.dims.data(), nullptr);
  s.precision = H5Tget_size(type.get());
  switch (H5Tget_class(type.get())) {
    case H5T_FLOAT:
      s.number_type = "Float";
      break;
    case H5T_INTEGER: {
      const bool is_signed = H5Tget_sign(type.get()) == H5T_SGN_2;
      s.number_type = s.precision == 1 ? (is_signed ? "Char" : "UChar") : (is_signed ? "Int" : "UInt");
      break;
    }
    default:
      return std::nullopt;  // strings and compound types: nothing to show
  }
  return s;
}

// Names of the links directly under a group, in name order.
std::vector<std::string> children(const Group& g) {
  std::vector<std::string> out;
  H5G_info_t info;
  if (H5Gget_info(g.id(), &info) < 0) return out;
  for (hsize_t k = 0; k < info.nlinks; ++k) {
    const ssize_t len = H5Lget_name_by_idx(g.id(), ".", H5_INDEX_NAME, H5_ITER_INC, k, nullptr, 0, H5P_DEFAULT);
    if (len <= 0) continue;
    std::string name(static_cast<std::size_t>(len) + 1, '\0');
    H5Lget_name_by_idx(g.id(), ".", H5_INDEX_NAME, H5_ITER_INC, k, name.data(), name.size(), H5P_DEFAULT);
    name.resize(static_cast<std::size_t>(len));
    out.push_back(name);
  }
  return out;
}

std::string dims_text(const std::vector<hsize_t>& dims) {
  std::string out;
  for (auto d : dims) out += (out.empty() ? "" : " ") + std::to_string(d);
  return out;
}

void append_number(std::string& out, double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 12);
  out.append(buf, r.ptr);
}

std::string number(double v, int digits = 17) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

class Writer {
 public:
  std::string text;
  void line(int indent, const std::string& s) {
    text.append(static_cast<std::size_t>(2 * indent), ' ');
    text += s;
    text += '\n';
  }
  // A whole HDF5 dataset.
  void hdf(int indent, const std::string& file, const std::string& path, const Shape& s) {
    line(indent, "<DataItem Dimensions=\"" + dims_text(s.dims) + "\" NumberType=\"" + s.number_type +
                     "\" Precision=\"" + std::to_string(s.precision) + "\" Format=\"HDF\">" + xml_escape(file) + ":" +
                     xml_escape(path) + "</DataItem>");
  }
  // Frame `frame` of a [T, ...] dataset, of shape [...]: the Xdmf 3 selection syntax or an XDMF 2
  // HyperSlab.
  XdmfFlavour flavour = XdmfFlavour::xdmf3;
  void frame_slab(int indent, const std::string& file, const std::string& path, const Shape& s, std::size_t frame) {
    const std::vector<hsize_t> result(s.dims.begin() + 1, s.dims.end());
    const std::size_t rank = s.dims.size();
    std::string start = std::to_string(frame), stride = "1", count = "1";
    for (std::size_t k = 1; k < rank; ++k) {
      start += " 0";
      stride += " 1";
      count += " " + std::to_string(s.dims[k]);
    }
    if (flavour == XdmfFlavour::xdmf3) {
      line(indent, "<DataItem Dimensions=\"" + dims_text(result) + "\" NumberType=\"" + s.number_type +
                       "\" Precision=\"" + std::to_string(s.precision) + "\" Format=\"HDF\">" + xml_escape(file) + ":" +
                       xml_escape(path) + "|" + start + ":" + stride + ":" + count + ":" + dims_text(s.dims) +
                       "</DataItem>");
      return;
    }
    line(indent, "<DataItem ItemType=\"HyperSlab\" Type=\"HyperSlab\" Dimensions=\"" + dims_text(result) + "\">");
    line(indent + 1, "<DataItem Dimensions=\"3 " + std::to_string(rank) + "\" NumberType=\"Int\" Format=\"XML\">" +
                         start + "  " + stride + "  " + count + "</DataItem>");
    hdf(indent + 1, file, path, s);
    line(indent, "</DataItem>");
  }
};

struct Field {
  std::string name;  // attribute name
  std::string path;  // dataset path, absolute
  Shape shape;
  bool series = false;  // value [T, ...]: one hyperslab per frame
  std::string file;     // which HDF5 file (the data file or the fragments file)
};

const char* attribute_type(const Shape& s, bool series) {
  const std::size_t rank = s.dims.size() - (series ? 1 : 0);
  return rank == 2 ? "Vector" : "Scalar";
}

// Per-entity fields of a group: datasets of shape [n] or [n, 2] (static) and time series whose value
// is [T, n] or [T, n, 2] with T = frames (series), skipping the names in `skip`.
std::vector<Field> fields_of(const Group& root, const std::string& group, std::size_t n, std::size_t frames,
                             const std::vector<std::string>& skip, const std::string& file,
                             std::vector<std::string>& notes) {
  std::vector<Field> out;
  if (!root.has(group)) return out;
  const Group g = root.group(group);
  auto fits = [&](const std::vector<hsize_t>& d, std::size_t first) {
    const std::size_t rank = d.size() - first;
    return (rank == 1 || (rank == 2 && d[first + 1] == 2)) && d[first] == n;
  };
  for (const auto& name : children(g)) {
    if (std::find(skip.begin(), skip.end(), name) != skip.end()) continue;
    const std::string path = "/" + group + "/" + name;
    if (auto s = dataset_shape(g, name)) {
      if (!s->dims.empty() && fits(s->dims, 0)) out.push_back({name, path, *s, false, file});
    } else if (frames > 0 && g.has(name + "/value")) {
      auto v = dataset_shape(g, name + "/value");
      if (!v || v->dims.size() < 2 || !fits(v->dims, 1)) continue;
      if (v->dims[0] != frames) {
        notes.push_back(path + "/value: " + std::to_string(v->dims[0]) + " frames, the trajectory has " +
                        std::to_string(frames) + "; left out");
        continue;
      }
      out.push_back({name, path + "/value", *v, true, file});
    }
  }
  return out;
}

void attributes(Writer& w, int indent, const std::vector<Field>& fields, const char* center, std::size_t frame) {
  for (const auto& f : fields) {
    w.line(indent, "<Attribute Name=\"" + xml_escape(f.name) + "\" AttributeType=\"" +
                       attribute_type(f.shape, f.series) + "\" Center=\"" + center + "\">");
    if (f.series)
      w.frame_slab(indent + 1, f.file, f.path, f.shape, frame);
    else
      w.hdf(indent + 1, f.file, f.path, f.shape);
    w.line(indent, "</Attribute>");
  }
}

// What a sidecar describes: the file's kind, its groups, sizes and reference shapes, and the fields shown.
struct Sidecar {
  std::string kind;
  bool run = false, cells = true;
  std::string body_group, link_group, body_name, link_name, ref_name;
  std::string file;                      // the data file, as the sidecar names it
  std::size_t n = 0, b = 0, frames = 0;  // bodies, links, frames
  std::optional<Shape> ref, pairs, position;
  std::vector<double> time;
  std::vector<Field> body_fields, link_fields, statics;
  bool polygons = false;
};

// Sizes: bodies from the reference geometry, links from the pairs, frames from position/time.
void read_sizes(const Group& root, Sidecar& s) {
  const Group bodies = root.group(s.body_group);
  s.ref = dataset_shape(bodies, s.ref_name);
  if (!s.ref || s.ref->dims.size() != 2 || s.ref->dims[1] != 2 || s.ref->number_type != "Float")
    throw InputError(bodies.where(s.ref_name) + ": missing, or not [N,2] floating point");
  s.n = s.ref->dims[0];
  const Group links = root.group(s.link_group);
  s.pairs = dataset_shape(links, "pairs");
  if (!s.pairs || s.pairs->dims.size() != 2 || s.pairs->dims[1] != 2 || s.pairs->number_type == "Float")
    throw InputError(links.where("pairs") + ": missing, or not [B,2] integers");
  s.b = s.pairs->dims[0];
  if (s.run) {
    s.time = bodies.read<double>("position/time", nullptr, 1);
    s.position = dataset_shape(bodies, "position/value");
    if (!s.position || s.position->dims.size() != 3 || s.position->dims[0] != s.time.size() ||
        s.position->dims[1] != s.n || s.position->dims[2] != 2 || s.position->number_type != "Float")
      throw InputError(bodies.where("position/value") + ": not [T,N,2] floating point with T = length of time");
  }
  s.frames = s.time.size();
}

// Attributes: every per-body and per-link dataset and time series, and the fragment labels.
// (A run's points move: the reference geometry is left out of their attributes.)
void collect_fields(const Group& root, const XdmfOptions& opt, Sidecar& s, std::vector<std::string>& notes) {
  std::vector<std::string> skip{"position", "vertex_offset", "vertex"};
  if (s.run) skip.push_back(s.ref_name);
  s.body_fields = fields_of(root, s.body_group, s.n, s.frames, skip, s.file, notes);
  s.link_fields = fields_of(root, s.link_group, s.b, s.frames, {"pairs"}, s.file, notes);
  if (s.run) {
    for (auto& f : fields_of(root, s.link_group + "/trajectory", s.b, s.frames, {}, s.file, notes)) {
      // The trajectory's intact flags override the mesh's static ones (rubber: the notch).
      std::erase_if(s.link_fields, [&](const Field& x) { return x.name == f.name; });
      s.link_fields.push_back(std::move(f));
    }
  }
  if (opt.fragments) {
    if (!s.cells) throw UsageError("--fragments: " + root.file() + " is a rubber-lattice file; fragments label cells");
    check_header(*opt.fragments, {"fragments"});
    const auto shape = dataset_shape(*opt.fragments, "fragments/cell_fragment");
    if (!shape || shape->dims.size() != 1 || shape->number_type == "Float")
      throw InputError(opt.fragments->where("fragments/cell_fragment") + ": missing, or not a column of integers");
    if (shape->dims[0] != s.n)
      throw InputError(opt.fragments->where("fragments/cell_fragment") + ": labels " + std::to_string(shape->dims[0]) +
                       " cells, " + root.file() + " has " + std::to_string(s.n) + " (fragments of another run?)");
    s.body_fields.push_back({"fragment", "/fragments/cell_fragment", *shape, false, opt.fragments_file});
  }
}

// Shared by every grid of points (each refers to it by XInclude; it is the first element of the
// Domain): the Polyvertex topology, whose connectivity 0 .. N-1 no dataset of the file holds. The
// whole Topology is shared, not its DataItem: Xdmf3 moves an inline array into the first topology
// that takes it, leaving nothing for the others.
void write_points_topology(Writer& w, std::size_t n) {
  w.line(2, "<Topology Name=\"points\" TopologyType=\"Polyvertex\" NumberOfElements=\"" + std::to_string(n) +
                "\" NodesPerElement=\"1\">");
  w.line(3, "<DataItem Dimensions=\"" + std::to_string(n) + "\" NumberType=\"Int\" Precision=\"8\" Format=\"XML\">");
  std::string ids;
  for (std::size_t i = 0; i < n; ++i) {
    ids += std::to_string(i);
    ids += (i + 1) % 20 == 0 || i + 1 == n ? '\n' : ' ';
  }
  w.text += ids;
  w.line(3, "</DataItem>");
  w.line(2, "</Topology>");
}

// Whether the reference polygons go inline: --polygons on, or automatic within the inline vertex limit
// (with a note when they are left out).
bool inline_polygons(const Group& root, const Sidecar& s, const XdmfOptions& opt, std::vector<std::string>& notes) {
  if (!s.cells) return false;
  const auto vertex = dataset_shape(root.group(s.body_group), "vertex");
  const std::size_t vertices = vertex && !vertex->dims.empty() ? vertex->dims[0] : 0;
  const bool polygons = opt.polygons == XdmfPolygons::on ||
                        (opt.polygons == XdmfPolygons::automatic && vertices <= opt.inline_vertex_limit);
  if (!polygons && opt.polygons == XdmfPolygons::automatic)
    notes.push_back("polygons left out: " + std::to_string(vertices) + " vertices is above the inline limit of " +
                    std::to_string(opt.inline_vertex_limit) + " (--polygons on writes them anyway)");
  return polygons;
}

// The polygons of the reference state, inline (their world vertices are stored nowhere): a Mixed
// topology of Polygon elements and its geometry, the second and third elements of the Domain, shared
// by the polygon grids.
void write_polygons(Writer& w, const mesh::CellMesh& m, XdmfReport& rep) {
  std::string topo, geom;
  std::size_t length = 0;
  for (std::size_t k = 0; k < m.cells(); ++k) {
    const auto poly = m.world_polygon(k);
    const std::size_t first = static_cast<std::size_t>(m.vertex_offset[k]);
    topo += "3 " + std::to_string(poly.size());
    length += 2 + poly.size();
    for (std::size_t j = 0; j < poly.size(); ++j) {
      topo += ' ';
      topo += std::to_string(first + j);
      append_number(geom, poly[j].x());
      geom += ' ';
      append_number(geom, poly[j].y());
      geom += '\n';
    }
    topo += '\n';
  }
  rep.polygon_vertices = m.vertex.size();
  w.line(2, "<Topology Name=\"reference_polygons\" TopologyType=\"Mixed\" NumberOfElements=\"" +
                std::to_string(m.cells()) + "\">");
  w.line(3,
         "<DataItem Dimensions=\"" + std::to_string(length) + "\" NumberType=\"Int\" Precision=\"8\" Format=\"XML\">");
  w.text += topo;
  w.line(3, "</DataItem>");
  w.line(2, "</Topology>");
  w.line(2, "<Geometry Name=\"reference_polygons\" GeometryType=\"XY\">");
  w.line(3, "<DataItem Dimensions=\"" + std::to_string(m.vertex.size()) +
                " 2\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">");
  w.text += geom;
  w.line(3, "</DataItem>");
  w.line(2, "</Geometry>");
}

// A polygon grid: the reference state, at every frame of a run (it does not move: ParaView's Xdmf3
// readers drop a grid without a time from a file whose other grids have times).
void polygons_grid(Writer& w, const Sidecar& s, int indent, std::optional<std::size_t> frame) {
  w.line(indent, "<Grid Name=\"reference_polygons\" GridType=\"Uniform\">");
  if (frame) w.line(indent + 1, "<Time Value=\"" + number(s.time[*frame]) + "\"/>");
  w.line(indent + 1, "<xi:include xpointer=\"element(/1/1/2)\"/>");
  w.line(indent + 1, "<xi:include xpointer=\"element(/1/1/3)\"/>");
  attributes(w, indent + 1, s.statics, "Cell", 0);
  w.line(indent, "</Grid>");
}

// The points' geometry: a frame's positions, or the reference geometry of a mesh.
void points_geometry(Writer& w, const Sidecar& s, int indent, std::optional<std::size_t> frame) {
  w.line(indent, "<Geometry GeometryType=\"XY\">");
  if (frame)
    w.frame_slab(indent + 1, s.file, "/" + s.body_group + "/position/value", *s.position, *frame);
  else
    w.hdf(indent + 1, s.file, "/" + s.body_group + "/" + s.ref_name, *s.ref);
  w.line(indent, "</Geometry>");
}

void points_grid(Writer& w, const Sidecar& s, int indent, std::optional<std::size_t> frame) {
  w.line(indent, "<Grid Name=\"" + s.body_name + "\" GridType=\"Uniform\">");
  if (frame) w.line(indent + 1, "<Time Value=\"" + number(s.time[*frame]) + "\"/>");
  w.line(indent + 1, "<xi:include xpointer=\"element(/1/1/1)\"/>");  // the shared points topology
  points_geometry(w, s, indent + 1, frame);
  attributes(w, indent + 1, s.body_fields, "Node", frame.value_or(0));
  w.line(indent, "</Grid>");
}

void links_grid(Writer& w, const Sidecar& s, int indent, std::optional<std::size_t> frame) {
  w.line(indent, "<Grid Name=\"" + s.link_name + "\" GridType=\"Uniform\">");
  if (frame) w.line(indent + 1, "<Time Value=\"" + number(s.time[*frame]) + "\"/>");
  w.line(indent + 1,
         "<Topology TopologyType=\"Polyline\" NumberOfElements=\"" + std::to_string(s.b) + "\" NodesPerElement=\"2\">");
  w.hdf(indent + 2, s.file, "/" + s.link_group + "/pairs", *s.pairs);
  w.line(indent + 1, "</Topology>");
  points_geometry(w, s, indent + 1, frame);
  attributes(w, indent + 1, s.link_fields, "Cell", frame.value_or(0));
  w.line(indent, "</Grid>");
}

// A temporal collection of one grid per frame.
void temporal_collection(Writer& w, const Sidecar& s, const std::string& name,
                         void (*grid)(Writer&, const Sidecar&, int, std::optional<std::size_t>)) {
  w.line(2, "<Grid Name=\"" + name + "\" GridType=\"Collection\" CollectionType=\"Temporal\">");
  for (std::size_t k = 0; k < s.frames; ++k) grid(w, s, 3, k);
  w.line(2, "</Grid>");
}

// Points and links: one grid each for a mesh, a temporal collection of one grid per frame for a run.
void write_grids(Writer& w, const Sidecar& s) {
  if (!s.run) {
    if (s.polygons) polygons_grid(w, s, 2, std::nullopt);
    points_grid(w, s, 2, std::nullopt);
    if (s.b > 0) links_grid(w, s, 2, std::nullopt);
    return;
  }
  if (s.polygons) temporal_collection(w, s, "reference_polygons", polygons_grid);
  temporal_collection(w, s, s.body_name, points_grid);
  if (s.b > 0) temporal_collection(w, s, s.link_name, links_grid);
}

}  // namespace

std::string xdmf_document(const Group& root, const XdmfOptions& opt, XdmfReport* report) {
  Sidecar s;
  s.kind = check_header(root, {"mesh", "run"});
  s.run = s.kind == "run";
  s.cells = mesh_kind(root) == MeshKind::cells;
  // The mesh validated as every tool reads it: no sidecar for a mesh no tool may run on.
  std::optional<mesh::CellMesh> cell_mesh;
  if (s.cells)
    cell_mesh = read_cell_mesh(root);
  else
    read_node_mesh(root);
  s.body_group = s.cells ? "particles/cells" : "particles/nodes";
  s.link_group = s.cells ? "connectivity/beams" : "connectivity/bonds";
  s.body_name = s.cells ? "cells" : "nodes";
  s.link_name = s.cells ? "beams" : "bonds";
  s.ref_name = s.cells ? "centroid" : "reference_position";
  s.file = opt.data_file;
  XdmfReport rep;
  read_sizes(root, s);
  rep.bodies = s.n;
  rep.links = s.b;
  rep.frames = s.frames;
  collect_fields(root, opt, s, rep.notes);

  Writer w;
  w.flavour = opt.flavour;
  w.line(0, "<?xml version=\"1.0\" encoding=\"utf-8\"?>");
  w.line(0, std::string("<Xdmf Version=\"") + (opt.flavour == XdmfFlavour::xdmf3 ? "3.0" : "2.0") +
                "\" xmlns:xi=\"http://www.w3.org/2001/XInclude\">");
  w.line(1, "<Domain Name=\"" + xml_escape(s.file) + "\">");
  write_points_topology(w, s.n);
  s.polygons = inline_polygons(root, s, opt, rep.notes);
  if (s.polygons) write_polygons(w, *cell_mesh, rep);
  w.line(2, "<Information Name=\"fracture\" Value=\"XDMF sidecar of " + xml_escape(s.file) + " (" + s.kind + ", " +
                (s.cells ? "polygon cells" : "rubber nodes") + "): docs/xdmf.md\"/>");
  if (!opt.provenance.empty())
    w.line(2,
           "<Information Name=\"" + std::string(kProvenanceKey) + "\" Value=\"" + xml_escape(opt.provenance) + "\"/>");
  for (const auto& f : s.body_fields)
    if (!f.series) s.statics.push_back(f);
  write_grids(w, s);
  w.line(1, "</Domain>");
  w.line(0, "</Xdmf>");
  if (report) *report = rep;
  return std::move(w.text);
}

std::string relative_reference(const std::string& target, const std::string& from_file) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path abs_target = fs::absolute(target, ec).lexically_normal();
  const fs::path base =
      from_file == "-" ? fs::current_path(ec) : fs::absolute(from_file, ec).lexically_normal().parent_path();
  const fs::path rel = abs_target.lexically_relative(base);
  const std::string ref = rel.empty() ? abs_target.string() : rel.string();
  // XDMF writes "file:/dataset": a colon in the file's name would end the name there.
  if (ref.find(':') != std::string::npos)
    throw UsageError(target + ": XDMF cannot refer to a file whose path contains ':' (" + ref +
                     "); rename the file or link it under another name");
  return ref;
}

void write_text_file(const std::string& path, const std::string& text) { write_file_atomically(path, text); }

}  // namespace frac::io

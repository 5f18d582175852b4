#pragma once
// XDMF 3 sidecars (docs/xdmf.md): a small XML file beside a mesh or run file that lets ParaView and
// VisIt open it, referring to the HDF5 datasets in place (nothing is copied, the run file is not
// changed). What it describes:
//   polygons  the cells' polygons in the reference state (the mesh), topology "Mixed" of Polygon
//             elements with per-cell vertex counts; their world vertices (centroid + body-frame vertex)
//             are not stored in the file, so they are written inline in the XML (cell meshes only,
//             up to a size limit)
//   cells / nodes   one point per body; in a run, a temporal collection with one grid per trajectory
//             frame whose geometry is the frame's slab of position/value and whose attributes
//             are the frame's slabs of every other per-body time series (velocity, angle,
//             angular_velocity, ...), plus the static per-body datasets (mass, area, ...)
//   beams / bonds   polylines of two points between the bodies (/connectivity/*/pairs) over the same
//             geometry, with the frame's strain and intact flags as cell attributes
// The rotated polygons of later frames are not described: XDMF can only point at stored arrays, and
// run files store each cell's centroid and angle, not its turned vertices.
#include <cstddef>
#include <string>
#include <vector>

#include "io/hdf5.hpp"

namespace frac::io {

enum class XdmfPolygons { automatic, on, off };

// How one frame of a [T, ...] dataset is referenced (docs/xdmf.md):
//   xdmf3  the Xdmf 3 library's own selection syntax, "file.h5:/path|start:stride:count:dims", read
//          by ParaView's Xdmf3 readers (they read only that frame; they mis-order a multidimensional
//          HyperSlab DataItem, as libXdmf 3.0 does)
//   xdmf2  the XDMF 2 HyperSlab DataItem of the format's specification, for VisIt and ParaView's
//          legacy "XDMF Reader"
enum class XdmfFlavour { xdmf3, xdmf2 };

struct XdmfOptions {
  // How the sidecar names the HDF5 file: a path relative to the sidecar's folder (relative_reference).
  std::string data_file;
  // Optional fragments file (kind "fragments") of this run: its /fragments/cell_fragment becomes the
  // cell attribute "fragment". `fragments` is the opened file, `fragments_file` how the sidecar names it.
  const Group* fragments = nullptr;
  std::string fragments_file;
  XdmfPolygons polygons = XdmfPolygons::automatic;
  XdmfFlavour flavour = XdmfFlavour::xdmf3;
  std::size_t inline_vertex_limit = 500000;  // automatic: write the polygons up to this many vertices
  // The sidecar's own provenance (frac::provenance_line), an Information element named "provenance".
  std::string provenance;
};

struct XdmfReport {
  std::size_t bodies = 0, links = 0, frames = 0;  // frames 0 for a mesh
  std::size_t polygon_vertices = 0;               // written inline; 0 when the polygons were left out
  std::vector<std::string> notes;                 // what was left out, and why
};

// The XDMF document for a mesh or run file (InputError naming the file when it is neither, or when its
// mesh fails an invariant of mesh/check.hpp).
std::string xdmf_document(const Group& root, const XdmfOptions& options, XdmfReport* report = nullptr);

// `target` as a path relative to the folder of `from_file` ("-": the current folder), for references
// inside a sidecar; the absolute path when no relative one exists.
std::string relative_reference(const std::string& target, const std::string& from_file);

// Writes text to `path` atomically (a temporary file in the same folder, then rename); "-" writes to
// standard output. UsageError for a missing folder, RuntimeError when writing fails.
void write_text_file(const std::string& path, const std::string& text);

}  // namespace frac::io

#include "io/hdf5_copy.hpp"

#include <cerrno>
#include <vector>

#include "core/error.hpp"
#include "io/atomic_file.hpp"

namespace frac::io {
namespace {

struct Copy {
  const Group& to;
  std::string path;  // of the group being copied, for messages

  [[noreturn]] void fail(const std::string& what) const {
    const int error = errno;
    throw RuntimeError(to.where(path) + ": cannot copy the output so far (" + what + ": " +
                       write_failure(to.file(), error) + ")");
  }

  // Variable-length data read with the file's type is allocated by libhdf5: given back after the write.
  static void reclaim(hid_t type, hid_t space, void* buffer) {
    if (H5Tis_variable_str(type) > 0 || H5Tdetect_class(type, H5T_VLEN) > 0)
      H5Dvlen_reclaim(type, space, H5P_DEFAULT, buffer);
  }

  void attributes(hid_t src, hid_t dst) const {
    H5O_info_t info;
    if (H5Oget_info2(src, &info, H5O_INFO_NUM_ATTRS) < 0) fail("attributes");
    for (hsize_t k = 0; k < info.num_attrs; ++k) {
      Hid a(H5Aopen_by_idx(src, ".", H5_INDEX_NAME, H5_ITER_INC, k, H5P_DEFAULT, H5P_DEFAULT));
      const ssize_t length = H5Aget_name(a.get(), 0, nullptr);
      std::string name(static_cast<std::size_t>(std::max<ssize_t>(length, 0)), '\0');
      H5Aget_name(a.get(), name.size() + 1, name.data());
      Hid type(H5Aget_type(a.get())), space(H5Aget_space(a.get()));
      const hssize_t points = H5Sget_simple_extent_npoints(space.get());
      std::vector<unsigned char> buffer(static_cast<std::size_t>(std::max<hssize_t>(points, 1)) *
                                        H5Tget_size(type.get()));
      if (H5Aread(a.get(), type.get(), buffer.data()) < 0) fail("attribute " + name);
      Hid b(H5Acreate2(dst, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT));
      const bool written = b.get() >= 0 && H5Awrite(b.get(), type.get(), buffer.data()) >= 0;
      reclaim(type.get(), space.get(), buffer.data());
      if (!written) fail("attribute " + name);
    }
  }

  // The chunks as stored, one at a time: offsets over the grid of chunks, the first dimension slowest.
  void chunks(hid_t src, hid_t dst, hid_t dcpl, hid_t space, const std::string& name) const {
    const int rank = H5Sget_simple_extent_ndims(space);
    std::vector<hsize_t> dims(static_cast<std::size_t>(rank)), chunk(dims.size()), offset(dims.size(), 0);
    H5Sget_simple_extent_dims(space, dims.data(), nullptr);
    if (H5Pget_chunk(dcpl, rank, chunk.data()) != rank) fail(name);
    for (hsize_t d : dims)
      if (d == 0) return;
    std::vector<unsigned char> buffer;
    for (;;) {
      hsize_t bytes = 0;
      if (H5Dget_chunk_storage_size(src, offset.data(), &bytes) >= 0 && bytes > 0) {  // (0: never written)
        buffer.resize(bytes);
        std::uint32_t filters = 0;
        if (H5Dread_chunk(src, H5P_DEFAULT, offset.data(), &filters, buffer.data()) < 0) fail(name);
        if (H5Dwrite_chunk(dst, H5P_DEFAULT, filters, offset.data(), bytes, buffer.data()) < 0) fail(name);
      }
      int d = rank - 1;
      for (; d >= 0; --d) {
        offset[d] += chunk[d];
        if (offset[d] < dims[d]) break;
        offset[d] = 0;
      }
      if (d < 0) return;
    }
  }

  void dataset(hid_t src_parent, hid_t dst_parent, const std::string& name) const {
    Hid src(H5Dopen2(src_parent, name.c_str(), H5P_DEFAULT));
    Hid type(H5Dget_type(src.get())), space(H5Dget_space(src.get())), dcpl(H5Dget_create_plist(src.get()));
    Hid dst(H5Dcreate2(dst_parent, name.c_str(), type.get(), space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT));
    if (dst.get() < 0) fail(name);
    if (H5Pget_layout(dcpl.get()) == H5D_CHUNKED) {
      chunks(src.get(), dst.get(), dcpl.get(), space.get(), name);
    } else {
      const hssize_t points = H5Sget_simple_extent_npoints(space.get());
      std::vector<unsigned char> buffer(static_cast<std::size_t>(std::max<hssize_t>(points, 1)) *
                                        H5Tget_size(type.get()));
      if (H5Dread(src.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()) < 0) fail(name);
      const bool written = H5Dwrite(dst.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()) >= 0;
      reclaim(type.get(), space.get(), buffer.data());
      if (!written) fail(name);
    }
    attributes(src.get(), dst.get());
  }

  void members(hid_t src, hid_t dst) const {
    H5G_info_t info;
    if (H5Gget_info(src, &info) < 0) fail("members");
    for (hsize_t k = 0; k < info.nlinks; ++k) {
      const ssize_t length = H5Lget_name_by_idx(src, ".", H5_INDEX_NAME, H5_ITER_INC, k, nullptr, 0, H5P_DEFAULT);
      std::string name(static_cast<std::size_t>(std::max<ssize_t>(length, 0)), '\0');
      H5Lget_name_by_idx(src, ".", H5_INDEX_NAME, H5_ITER_INC, k, name.data(), name.size() + 1, H5P_DEFAULT);
      H5O_info_t object;
      if (H5Oget_info_by_name2(src, name.c_str(), &object, H5O_INFO_BASIC, H5P_DEFAULT) < 0) fail(name);
      if (object.type == H5O_TYPE_DATASET) {
        dataset(src, dst, name);
      } else if (object.type == H5O_TYPE_GROUP) {
        Hid s(H5Gopen2(src, name.c_str(), H5P_DEFAULT));
        Hid d(H5Gcreate2(dst, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
        if (d.get() < 0) fail(name);
        members(s.get(), d.get());
        attributes(s.get(), d.get());
      }
    }
  }
};

}  // namespace

void copy_group(const Group& from, const std::string& path, Group& to) {
  const Group src = from.group(path);
  Group dst = to.create_group(path);
  const Copy copy{to, path};
  copy.members(src.id(), dst.id());
  copy.attributes(src.id(), dst.id());
}

}  // namespace frac::io

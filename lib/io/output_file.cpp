#include "io/output_file.hpp"

#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <vector>

#include "core/error.hpp"
#include "core/memory.hpp"
#include "core/provenance.hpp"

namespace frac::io {
namespace {

Hid file_access(bool in_memory) {
  Hid fapl(H5Pcreate(H5P_FILE_ACCESS));
  // Strong close: closing the file closes every object still open in it, so commit() can rename.
  H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG);
  // io/atomic_file locks the temporary file itself (its lock marks a live writer); libhdf5's own lock
  // on the same file would conflict with it.
  H5Pset_file_locking(fapl.get(), false, true);
  if (in_memory) H5Pset_fapl_core(fapl.get(), 16u << 20, 0);
  return fapl;
}

}  // namespace

OutputFile::OutputFile(std::string path) : path_(std::move(path)), uuid_(make_uuid()) {
  silence_hdf5_errors();
  const OutputTarget target = resolve_output(path_);
  if (target.kind == OutputKind::standard_output && isatty(STDOUT_FILENO))
    throw UsageError("refusing to write an HDF5 file to a terminal: give -o FILE or redirect standard output");
  if (target.kind == OutputKind::stream) stream_ = std::make_unique<OutputStream>(target.path, true);
  if (target.kind != OutputKind::file) {
    Hid fapl = file_access(true);
    file_ = Hid(H5Fcreate(("memory-" + uuid_ + ".h5").c_str(), H5F_ACC_EXCL, H5P_DEFAULT, fapl.get()));
    if (file_.get() < 0) throw RuntimeError(path_ + ": cannot create the in-memory HDF5 file");
  } else {
    atomic_ = std::make_unique<AtomicFile>(target.path);
    Hid fapl = file_access(false);
    file_ = Hid(H5Fcreate(atomic_->path().c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()));
    if (file_.get() < 0) throw RuntimeError(path_ + ": cannot create the file (" + write_failure(path_, errno) + ")");
  }
  root_.emplace(Hid(H5Gopen2(file_.get(), "/", H5P_DEFAULT)), path_, "/");
}

OutputFile::~OutputFile() {
  if (committed_) return;
  root_.reset();
  file_.reset();  // closed before ~AtomicFile removes the temporary file
}

void OutputFile::commit(bool durable) {
  if (committed_) return;
  if (!atomic_) {
    if (H5Fflush(file_.get(), H5F_SCOPE_GLOBAL) < 0) throw RuntimeError(path_ + ": cannot finish the HDF5 file");
    const ssize_t size = H5Fget_file_image(file_.get(), nullptr, 0);
    if (size <= 0) throw RuntimeError(path_ + ": cannot take the HDF5 file image");
    std::vector<char> image;
    try {
      image.resize(static_cast<std::size_t>(size));
    } catch (const std::bad_alloc&) {
      throw out_of_memory("the HDF5 image of " + path_);
    }
    if (H5Fget_file_image(file_.get(), image.data(), image.size()) != size)
      throw RuntimeError(path_ + ": cannot take the HDF5 file image");
    root_.reset();
    file_.reset();
    if (stream_)
      stream_->write(image.data(), image.size());
    else
      write_standard_output(image.data(), image.size());
  } else {
    root_.reset();
    if (H5Fclose(file_.release()) < 0)
      throw RuntimeError(path_ + ": cannot finish writing the file (" + write_failure(path_, errno) + ")");
    atomic_->commit(durable);
  }
  committed_ = true;
}

}  // namespace frac::io

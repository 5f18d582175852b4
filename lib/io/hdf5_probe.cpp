#include "io/hdf5_probe.hpp"

#include <fcntl.h>
#include <hdf5.h>
#include <hdf5_hl.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>

#include "core/error.hpp"
#include "core/memory.hpp"
#include "io/hdf5.hpp"

namespace frac::io {
namespace {

// The child stops with "stalled" when it reports nothing for this long; a healthy walk reports every
// object, attribute and 4096 chunks.
constexpr int kStallMilliseconds = 5000;
// Limits of the walk: objects and chunks visited, bytes of one attribute or string dataset.
constexpr long kMaxObjects = 10'000'000;
constexpr hsize_t kMaxChunks = 100'000'000;
constexpr hsize_t kMaxReadBytes = hsize_t{1} << 30;
// Memory the child may add to what it inherits.
constexpr rlim_t kChildMemory = rlim_t{1} << 30;

// ---- the child ----

int g_report = -1;  // the pipe to the parent

// Messages to the parent: a type byte, the payload's length (8 bytes), the payload. '@' the object being
// read, '.' progress, '!' damaged (where, tab, why), 'k' done, 's' strings (see send_strings).
void send(char type, const std::string& payload = "") {
  std::string m(1, type);
  const std::uint64_t n = payload.size();
  m.append(reinterpret_cast<const char*>(&n), sizeof n);
  m += payload;
  for (const char* p = m.data(); !m.empty();) {
    const ssize_t w = write(g_report, p, m.size());
    if (w <= 0) _exit(5);
    m.erase(0, static_cast<std::size_t>(w));
  }
}

void append_u64(std::string& s, std::uint64_t v) { s.append(reinterpret_cast<const char*>(&v), sizeof v); }

// The strings of an object's attribute `attr` ("" for a dataset's values), for the parent's cache.
void send_strings(haddr_t object, const std::string& attr, char* const* values, std::size_t count) {
  std::string m;
  append_u64(m, object);
  append_u64(m, attr.size());
  m += attr;
  append_u64(m, count);
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t n = values[k] ? std::strlen(values[k]) : 0;
    append_u64(m, n);
    m.append(values[k] ? values[k] : "", n);
  }
  send('s', m);
}

[[noreturn]] void damaged(const std::string& where, const std::string& why) {
  // (libhdf5 out of memory is no fault of the file)
  send(hdf5_out_of_memory() ? 'm' : '!', where + "\t" + why);
  _exit(3);
}

// Reads `count` elements through `read` into memory of the native type of `ftype`, then frees what
// variable-length data the read allocated (described by `mem_space`).
template <class Read>
void read_native(hid_t ftype, hid_t mem_space, hssize_t count, const std::string& where, Read&& read) {
  const H5T_class_t cls = H5Tget_class(ftype);
  if ((cls == H5T_INTEGER || cls == H5T_FLOAT) && !standard_number_type(ftype))
    damaged(where, "damaged or unusual number type");  // the readers refuse it without converting
  Hid mtype(H5Tget_native_type(ftype, H5T_DIR_ASCEND));
  if (mtype.get() < 0) damaged(where, "unreadable datatype");
  const std::size_t size = H5Tget_size(mtype.get());
  if (count < 0 || size == 0) damaged(where, "unreadable datatype or dataspace");
  if (static_cast<hsize_t>(count) > kMaxReadBytes / size) damaged(where, "implausibly large");
  std::vector<unsigned char> buf(static_cast<std::size_t>(count) * size + 1, 0);
  if (count > 0 && read(mtype.get(), buf.data()) < 0) damaged(where, "cannot be read");
  if (count > 0 && H5Tdetect_class(mtype.get(), H5T_VLEN) + H5Tis_variable_str(mtype.get()) > 0)
    H5Dvlen_reclaim(mtype.get(), mem_space, H5P_DEFAULT, buf.data());
}

struct Walk {
  long objects = 0;
  std::string path;  // of the object being walked
  haddr_t address = 0;
};

// Variable-length strings through `read` (count of them, described by `space`): read, sent, freed.
template <class Read>
void walk_strings(hid_t file_type, hid_t space, hssize_t count, haddr_t object, const std::string& attr,
                  const std::string& where, Read&& read) {
  if (count < 0 || static_cast<hsize_t>(count) > kMaxReadBytes / sizeof(char*)) damaged(where, "implausibly large");
  Hid type(H5Tcopy(H5T_C_S1));
  H5Tset_size(type.get(), H5T_VARIABLE);
  H5Tset_cset(type.get(), H5Tget_cset(file_type));  // (libhdf5 converts neither way between ASCII and UTF-8)
  std::vector<char*> values(static_cast<std::size_t>(count) + 1, nullptr);
  if (count > 0 && read(type.get(), values.data()) < 0) damaged(where, "strings cannot be read");
  send_strings(object, attr, values.data(), static_cast<std::size_t>(count));
  if (count > 0) H5Dvlen_reclaim(type.get(), space, H5P_DEFAULT, values.data());
}

bool variable_strings(hid_t type) { return H5Tget_class(type) == H5T_STRING && H5Tis_variable_str(type) > 0; }

herr_t visit_attribute(hid_t object, const char* name, const H5A_info_t*, void* data) {
  const auto& walk = *static_cast<const Walk*>(data);
  const std::string where = walk.path + " attribute '" + name + "'";
  send('@', where);
  Hid a(H5Aopen(object, name, H5P_DEFAULT));
  if (a.get() < 0) damaged(where, "cannot be opened");
  Hid type(H5Aget_type(a.get())), space(H5Aget_space(a.get()));
  if (type.get() < 0 || space.get() < 0) damaged(where, "unreadable datatype or dataspace");
  auto read = [&](hid_t mtype, void* buf) { return H5Aread(a.get(), mtype, buf); };
  if (variable_strings(type.get()))
    walk_strings(type.get(), space.get(), H5Sget_simple_extent_npoints(space.get()), walk.address, name, where, read);
  else
    read_native(type.get(), space.get(), H5Sget_simple_extent_npoints(space.get()), where, read);
  return 0;
}

void walk_dataset(hid_t d, haddr_t address, const std::string& where) {
  Hid type(H5Dget_type(d)), space(H5Dget_space(d)), dcpl(H5Dget_create_plist(d));
  if (type.get() < 0 || space.get() < 0 || dcpl.get() < 0) damaged(where, "unreadable datatype, dataspace or layout");
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0 || rank > H5S_MAX_RANK) damaged(where, "unreadable dataspace");
  const hssize_t count = H5Sget_simple_extent_npoints(space.get());
  if (count < 0) damaged(where, "unreadable dataspace");
  const int filters = H5Pget_nfilters(dcpl.get());
  for (int k = 0; k < filters; ++k) {
    unsigned flags = 0, config = 0;
    std::size_t values = 8;
    unsigned cd[8];
    char filter_name[64];
    if (H5Pget_filter2(dcpl.get(), static_cast<unsigned>(k), &flags, &values, cd, sizeof filter_name, filter_name,
                       &config) < 0)
      damaged(where, "unreadable filter pipeline");
  }
  if (H5Pget_layout(dcpl.get()) == H5D_CHUNKED) {
    hsize_t chunks = 0;
    if (H5Dget_num_chunks(d, space.get(), &chunks) < 0) damaged(where, "unreadable chunk index");
    if (chunks > kMaxChunks) damaged(where, "implausible chunk count");
    std::vector<hsize_t> offset(static_cast<std::size_t>(rank) + 1);
    for (hsize_t c = 0; c < chunks; ++c) {
      unsigned mask = 0;
      haddr_t chunk_address = 0;
      hsize_t bytes = 0;
      if (H5Dget_chunk_info(d, space.get(), c, offset.data(), &mask, &chunk_address, &bytes) < 0)
        damaged(where, "unreadable chunk index");
      if (c % 4096 == 4095) send('.');
    }
  }
  if (count == 0) return;
  if (H5Tget_class(type.get()) == H5T_STRING) {  // strings (provenance, names): small, read whole
    auto read = [&](hid_t mtype, void* buf) { return H5Dread(d, mtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf); };
    if (variable_strings(type.get()))
      walk_strings(type.get(), space.get(), count, address, "", where, read);
    else
      read_native(type.get(), space.get(), count, where, read);
    return;
  }
  // One element, through the chunk or block that holds it and the type conversion a reader uses.
  std::vector<hsize_t> start(static_cast<std::size_t>(std::max(rank, 1)), 0), one(start.size(), 1);
  if (rank > 0 && H5Sselect_hyperslab(space.get(), H5S_SELECT_SET, start.data(), nullptr, one.data(), nullptr) < 0)
    damaged(where, "unreadable dataspace");
  const hsize_t single = 1;
  Hid memory(H5Screate_simple(1, &single, nullptr));
  read_native(type.get(), memory.get(), 1, where,
              [&](hid_t mtype, void* buf) { return H5Dread(d, mtype, memory.get(), space.get(), H5P_DEFAULT, buf); });
}

herr_t visit_object(hid_t root, const char* name, const H5O_info_t* info, void* data) {
  auto& walk = *static_cast<Walk*>(data);
  if (++walk.objects > kMaxObjects) damaged(walk.path, "implausibly many objects");
  walk.path = std::strcmp(name, ".") == 0 ? "/" : "/" + std::string(name);
  walk.address = info->addr;
  send('@', walk.path);
  Hid o(H5Oopen(root, name, H5P_DEFAULT));
  if (o.get() < 0) damaged(walk.path, "cannot be opened");
  hsize_t index = 0;
  if (H5Aiterate2(o.get(), H5_INDEX_NAME, H5_ITER_NATIVE, &index, visit_attribute, &walk) < 0)
    damaged(walk.path, "unreadable attributes");
  if (info->type == H5O_TYPE_DATASET) walk_dataset(o.get(), walk.address, walk.path);
  return 0;
}

[[noreturn]] void child(const std::string& name, const std::vector<char>* image) {
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) std::signal(sig, SIG_DFL);  // not the parent's temp cleanup
#if !defined(__SANITIZE_ADDRESS__)
  // The address space the parent left us, plus a budget: a corrupt size fails to allocate instead of
  // taking the machine's memory.
  if (std::FILE* f = std::fopen("/proc/self/statm", "r")) {
    unsigned long pages = 0;
    if (std::fscanf(f, "%lu", &pages) == 1) {
      const rlim_t limit = static_cast<rlim_t>(pages) * static_cast<rlim_t>(sysconf(_SC_PAGESIZE)) + kChildMemory;
      const rlimit r{limit, limit};
      setrlimit(RLIMIT_AS, &r);
    }
    std::fclose(f);
  }
#endif
  silence_hdf5_errors();
  hid_t file;
  if (image) {
    file = H5LTopen_file_image(const_cast<char*>(image->data()), image->size(),
                               H5LT_FILE_IMAGE_DONT_COPY | H5LT_FILE_IMAGE_DONT_RELEASE);
  } else {
    if (H5Fis_hdf5(name.c_str()) <= 0) damaged("", "not an HDF5 file");
    file = H5Fopen(name.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  }
  if (file < 0) damaged("", "cannot be opened (damaged HDF5 file, or no permission)");
  Walk walk;
  walk.path = "/";
  if (H5Ovisit2(file, H5_INDEX_NAME, H5_ITER_NATIVE, visit_object, &walk, H5O_INFO_BASIC) < 0)
    damaged(walk.path, "damaged object header or link table");
  send('k');
  _exit(0);
}

// ---- the parent ----

// Decodes an 's' message into `out`; false when it is malformed.
bool read_strings_message(const std::string& m, WalkedStrings& out) {
  std::size_t at = 0;
  auto u64 = [&](std::uint64_t& v) {
    if (m.size() - at < sizeof v) return false;
    std::memcpy(&v, m.data() + at, sizeof v);
    at += sizeof v;
    return true;
  };
  auto text = [&](std::string& t) {
    std::uint64_t n;
    if (!u64(n) || m.size() - at < n) return false;
    t.assign(m, at, n);
    at += n;
    return true;
  };
  std::uint64_t address, count;
  std::string attr;
  if (!u64(address) || !text(attr) || !u64(count) || count > m.size()) return false;
  std::vector<std::string> values(count);
  for (auto& v : values)
    if (!text(v)) return false;
  out[{static_cast<haddr_t>(address), attr}] = std::move(values);
  return at == m.size();
}

std::string describe(const std::string& name, const std::string& where, const std::string& why) {
  return name + (where.empty() ? "" : ":" + where) + ": damaged HDF5 file (" + why + ")";
}

// What the checking child reported through its pipe: the strings it walked, the last object it opened, its
// verdict ("ok", "!where\twhy" or "m..."), and whether it stalled or sent what no child sends.
struct ChildReport {
  std::shared_ptr<WalkedStrings> strings = std::make_shared<WalkedStrings>();
  std::string last_object, verdict;
  bool stalled = false, garbled = false;
};

// Reads the child's messages (type, 8-byte length, payload) until it closes the pipe, stalls or garbles one.
ChildReport read_child_report(int fd) {
  ChildReport r;
  std::string received;
  bool done = false;
  while (!done) {
    pollfd p{fd, POLLIN, 0};
    const int ready = poll(&p, 1, kStallMilliseconds);
    if (ready < 0 && errno == EINTR) continue;
    if (ready == 0) {
      r.stalled = true;
      break;
    }
    char buf[1 << 16];
    const ssize_t n = read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    received.append(buf, static_cast<std::size_t>(n));
    std::size_t at = 0;
    while (received.size() - at >= 9) {
      std::uint64_t length;
      std::memcpy(&length, received.data() + at + 1, sizeof length);
      if (length > kMaxReadBytes) {
        r.garbled = done = true;
        break;
      }
      if (received.size() - at - 9 < length) break;
      const char type = received[at];
      const std::string payload = received.substr(at + 9, length);
      at += 9 + length;
      if (type == '@')
        r.last_object = payload;
      else if (type == '!' || type == 'm')
        r.verdict = std::string(1, type) + payload;
      else if (type == 'k')
        r.verdict = "ok";
      else if (type == 's' && !read_strings_message(payload, *r.strings))
        r.garbled = done = true;
    }
    received.erase(0, at);
  }
  return r;
}

// The error a failed check gives: the child's own verdict, else how it ended.
[[noreturn]] void refuse_checked_file(const std::string& name, const ChildReport& r, int status) {
  if (r.stalled) throw InputError(describe(name, r.last_object, "libhdf5 makes no progress reading it"));
  if (r.verdict.starts_with("m"))
    throw OutOfMemory("checking " + name + (r.last_object.empty() ? "" : ":" + r.last_object), 0);
  if (r.verdict.starts_with("!")) {
    const auto tab = r.verdict.find('\t');
    const std::string where = r.verdict.substr(1, tab - 1), why = r.verdict.substr(tab + 1);
    if (why == "not an HDF5 file") throw InputError(name + ": not an HDF5 file");
    throw InputError(describe(name, where, why));
  }
  if (WIFSIGNALED(status))
    throw InputError(
        describe(name, r.last_object, std::string("libhdf5 fails reading it: ") + strsignal(WTERMSIG(status))));
  throw InputError(describe(name, r.last_object, "libhdf5 cannot read it"));
}

}  // namespace

std::shared_ptr<const WalkedStrings> probe_hdf5_file(const std::string& name, const std::vector<char>* image) {
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) throw RuntimeError(name + ": cannot check the file (" + std::strerror(errno) + ")");
  std::fflush(nullptr);  // nothing buffered is written twice
  const pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]);
    close(fds[1]);
    throw RuntimeError(name + ": cannot check the file (" + std::strerror(errno) + ")");
  }
  if (pid == 0) {
    close(fds[0]);
    g_report = fds[1];
    try {
      child(name, image);
    } catch (const std::bad_alloc&) {
      send('m', "\tout of memory");
      _exit(4);
    } catch (...) {
      _exit(4);
    }
  }
  close(fds[1]);
  const ChildReport report = read_child_report(fds[0]);
  close(fds[0]);
  if (report.stalled || report.garbled) kill(pid, SIGKILL);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!report.stalled && WIFEXITED(status) && WEXITSTATUS(status) == 0 && report.verdict == "ok" && !report.garbled)
    return report.strings;
  refuse_checked_file(name, report, status);
}

}  // namespace frac::io

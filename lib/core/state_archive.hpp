#pragma once
// The state a run needs to continue exactly where it stopped (a checkpoint's content, io/checkpoint), as named
// arrays of numbers. An object that holds such state has one function, visit_state(StateArchive&), that names
// each of its arrays to the archive: saving, the archive takes them; loading, it fills them. Saving and loading
// run the same code, so what is saved and what is loaded cannot drift apart.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace frac {

class StateArchive {
 public:
  static constexpr std::size_t kAnySize = std::numeric_limits<std::size_t>::max();
  virtual ~StateArchive() = default;
  virtual bool loading() const = 0;

  // Saves v, or loads it: InputError naming the entry when it is missing, of another type or (unless `size` is
  // kAnySize) not `size` values long.
  void array(std::string_view name, std::vector<double>& v, std::size_t size = kAnySize) {
    entry(name, Type::float64, v, size);
  }
  void array(std::string_view name, std::vector<std::int64_t>& v, std::size_t size = kAnySize) {
    entry(name, Type::int64, v, size);
  }
  void array(std::string_view name, std::vector<std::uint8_t>& v, std::size_t size = kAnySize) {
    entry(name, Type::uint8, v, size);
  }
  // Arrays of other integers, stored as int64 (loading: InputError when a value does not fit T).
  template <class T>
  requires(std::is_integral_v<T> && !std::is_same_v<T, std::int64_t> &&
           !std::is_same_v<T, std::uint8_t>) void array(std::string_view name, std::vector<T>& v,
                                                        std::size_t size = kAnySize);

  // One number, as an array of one.
  template <class T>
  void value(std::string_view name, T& x) {
    std::vector<T> one{x};
    array(name, one, 1);
    x = one[0];
  }
  void value(std::string_view name, bool& x) {
    std::uint8_t b = x ? 1 : 0;
    value(name, b);
    if (b > 1) refuse(name, "holds " + std::to_string(b) + ", not 0 or 1");
    x = b != 0;
  }

  // One member of every record of `records` (loading: records already sized).
  template <class R, class F>
  void field(std::string_view name, std::vector<R>& records, F R::*member) {
    using Stored = std::conditional_t<std::is_floating_point_v<F>, double,
                                      std::conditional_t<std::is_same_v<F, bool>, std::uint8_t, F>>;
    std::vector<Stored> column(loading() ? 0 : records.size());
    if (!loading())
      for (std::size_t k = 0; k < records.size(); ++k) column[k] = static_cast<Stored>(records[k].*member);
    array(name, column, records.size());
    if (!loading()) return;
    for (std::size_t k = 0; k < records.size(); ++k) {
      if constexpr (std::is_same_v<F, bool>)
        if (column[k] > 1) refuse(name, "holds " + std::to_string(column[k]) + ", not 0 or 1");
      records[k].*member = static_cast<F>(column[k]);
    }
  }

  // The names that follow go under a prefix while the scope lives: Scope s(archive, "integrator") makes "r1"
  // "integrator/r1".
  class Scope {
   public:
    Scope(StateArchive& a, std::string_view name) : a_(a), saved_(a.prefix_.size()) {
      a.prefix_.append(name).push_back('/');
    }
    ~Scope() { a_.prefix_.resize(saved_); }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    StateArchive& a_;
    std::size_t saved_;
  };

  // InputError naming the entry: a loaded value the run cannot take (an index out of range).
  [[noreturn]] void refuse(std::string_view name, const std::string& why) const;
  // Loading: InputError naming the entry unless every value is below `bound`.
  template <class T>
  void require_below(std::string_view name, const std::vector<T>& v, std::size_t bound) const {
    for (const T& x : v)
      if (x < 0 || static_cast<std::size_t>(x) >= bound)
        refuse(name, "holds an index out of range (" + std::to_string(x) + ", of " + std::to_string(bound) + ")");
  }

 protected:
  enum class Type { float64, int64, uint8 };
  // Saving: `count` values of `type` at `data` under the full name. Loading: how many values the full name holds
  // (InputError if missing or of another type), then load() copies them.
  virtual void save(const std::string& name, Type type, const void* data, std::size_t count) = 0;
  virtual std::size_t stored(const std::string& name, Type type) = 0;
  virtual void load(const std::string& name, Type type, void* data, std::size_t count) = 0;
  // Where an entry is, for messages ("state.h5:/state/integrator/r1").
  virtual std::string where(const std::string& name) const = 0;

 private:
  template <class T>
  void entry(std::string_view name, Type type, std::vector<T>& v, std::size_t size) {
    const std::string full = prefix_ + std::string(name);
    if (!loading()) {
      save(full, type, v.data(), v.size());
      return;
    }
    const std::size_t n = stored(full, type);
    if (size != kAnySize && n != size)
      refuse(name, "holds " + std::to_string(n) + " values, the run needs " + std::to_string(size));
    v.resize(n);
    load(full, type, v.data(), n);
  }
  std::string prefix_;
};

template <class T>
requires(std::is_integral_v<T> && !std::is_same_v<T, std::int64_t> &&
         !std::is_same_v<T, std::uint8_t>) void StateArchive::array(std::string_view name, std::vector<T>& v,
                                                                    std::size_t size) {
  std::vector<std::int64_t> wide(v.begin(), v.end());
  array(name, wide, size);
  if (!loading()) return;
  v.resize(wide.size());
  for (std::size_t k = 0; k < wide.size(); ++k) {
    const std::int64_t x = wide[k];
    if (!std::in_range<T>(x)) refuse(name, "holds " + std::to_string(x) + ", out of the range of its type");
    v[k] = static_cast<T>(x);
  }
}

}  // namespace frac

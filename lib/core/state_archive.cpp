#include "core/state_archive.hpp"

#include "core/error.hpp"

namespace frac {

void StateArchive::refuse(std::string_view name, const std::string& why) const {
  throw InputError(where(prefix_ + std::string(name)) + ": " + why);
}

}  // namespace frac

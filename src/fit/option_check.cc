#include "fit/option_check.h"

#include <sstream>

namespace dynosize::fit {

bool OptionCheck::Fail(const char* field, double value, const char* rule) const {
  std::ostringstream os;
  os << owner_ << "." << field << " = " << value << " " << rule;
  if (error_ != nullptr) *error_ = os.str();
  return false;
}

bool OptionCheck::Fail(const char* field, const char* rule) const {
  if (error_ != nullptr) *error_ = std::string(owner_) + "." + field + " " + rule;
  return false;
}

}  // namespace dynosize::fit

// Options checked the Ceres way: `bool IsValid(std::string* error) const` on every options
// struct, naming the first violated rule as "Owner.field = value rule" (for example
// "DiagnoseOptions.folds = 1 must be >= 2"). OptionCheck writes that line; every options struct
// of src/fit, src/identification, src/calibration and src/diagnosis uses it.
#pragma once

#include <string>

namespace dynosize::fit {

class OptionCheck {
 public:
  // owner: the struct's name; error: where Fail writes its line (may be null).
  OptionCheck(const char* owner, std::string* error) : owner_(owner), error_(error) {}
  // Writes "owner.field = value rule" to *error and returns false (for `return check.Fail(...)`).
  bool Fail(const char* field, double value, const char* rule) const;
  // The same for a rule that involves no single value ("owner.field rule").
  bool Fail(const char* field, const char* rule) const;

 private:
  const char* owner_;
  std::string* error_;
};

}  // namespace dynosize::fit

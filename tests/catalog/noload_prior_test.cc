// The no-load prior (src/catalog/noload_prior.h): its bundled coefficients are the fit on the
// bundled catalog (refitted here, not assumed), and docs/noload-prior.md states the same numbers.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include "catalog/catalog.h"
#include "catalog/noload_prior.h"

namespace dynosize {
namespace {

const std::string kCatalog = DYNOSIZE_SOURCE_DIR "/catalog";
const std::string kDoc = DYNOSIZE_SOURCE_DIR "/docs/noload-prior.md";

// The bundled constants are rounded to 4 significant digits.
constexpr double kRoundingRel = 1e-3;

std::string Fixed(double v, int digits) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(digits);
  s << v;
  return s.str();
}

TEST(NoLoadPrior, BundledLawIsTheFitOnTheBundledCatalog) {
  // The files' datasheet values (Io at its test voltage), not the in-system law's (catalog/in_system.h).
  const Catalog c = Catalog::Load(kCatalog, /*in_system_law=*/false);
  const NoLoadLaw law = FitNoLoadLaw(c.motors());
  std::cout << "[no-load law] a " << law.a << " b " << law.b_imax << " c " << law.c_speed << " sd " << law.log10_sd
            << " p10 " << law.p10_factor << " p90 " << law.p90_factor << " motors " << law.motors << "\n";
  const NoLoadLaw& k = kBundledNoLoadLaw;
  EXPECT_NEAR(k.a, law.a, kRoundingRel * std::fabs(law.a));
  EXPECT_NEAR(k.b_imax, law.b_imax, kRoundingRel * std::fabs(law.b_imax));
  EXPECT_NEAR(k.c_speed, law.c_speed, kRoundingRel * std::fabs(law.c_speed));
  EXPECT_NEAR(k.log10_sd, law.log10_sd, kRoundingRel * law.log10_sd);
  EXPECT_NEAR(k.p10_factor, law.p10_factor, kRoundingRel * law.p10_factor);
  EXPECT_NEAR(k.p90_factor, law.p90_factor, kRoundingRel * law.p90_factor);
  EXPECT_EQ(k.motors, law.motors);
}

TEST(NoLoadPrior, DocStatesTheBundledLaw) {
  std::ifstream f(kDoc);
  ASSERT_TRUE(f) << kDoc;
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string doc = ss.str();
  const NoLoadLaw& k = kBundledNoLoadLaw;
  for (const std::string& s : {Fixed(k.a, 3), Fixed(k.b_imax, 4), Fixed(k.c_speed, 4), Fixed(k.log10_sd, 4),
                               Fixed(k.p10_factor, 3), Fixed(k.p90_factor, 3), std::to_string(k.motors)}) {
    EXPECT_NE(doc.find(s), std::string::npos) << "docs/noload-prior.md does not state " << s;
  }
}

TEST(NoLoadPrior, GrowsWithSizeAndSpeedAndRefusesNonsense) {
  const double io = NoLoadPriorIoA(30.0, 10000.0);
  EXPECT_GT(io, 0.0);
  EXPECT_GT(NoLoadPriorIoA(60.0, 10000.0), io);
  EXPECT_GT(NoLoadPriorIoA(30.0, 20000.0), io);
  EXPECT_TRUE(std::isnan(NoLoadPriorIoA(0.0, 10000.0)));
  EXPECT_TRUE(std::isnan(NoLoadPriorIoA(30.0, -1.0)));
}

}  // namespace
}  // namespace dynosize

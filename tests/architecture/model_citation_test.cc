// Every equation and section of docs/model.md that a comment cites exists there.
//
// The code cites the model as "docs/model.md eq 48", "eqs 41, 42, 47", "eqs 42-59" or
// "docs/model.md section 9". docs/model.md numbers its equations at the end of the line, "(48)",
// and some section headings name the equations they state in words, "## 4. ... (eqs 28-41)".
// A citation of a number the document does not hold is a dangling reference: the test names the
// file and line.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

const fs::path kRoot = DYNOSIZE_SOURCE_DIR;

// The numbers a citation lists: "4", "4-7", "4, 5 and 9". A range cited by the code ("eqs 42-59":
// the block of the model from 42 to 59) needs its two ends in the document; a range a heading of
// the document names ("## 4. ... (eqs 28-41)") states every equation inside it.
std::vector<int> CitedNumbers(const std::string& list, bool whole_ranges) {
  static const std::regex kNumberOrRange(R"re((\d+)(?:\s*-\s*(\d+))?)re");
  std::vector<int> out;
  for (std::sregex_iterator it(list.begin(), list.end(), kNumberOrRange), end; it != end; ++it) {
    const int a = std::stoi((*it)[1].str());
    const int b = (*it)[2].matched ? std::stoi((*it)[2].str()) : a;
    if (!whole_ranges) {
      out.push_back(a);
      if (b != a) out.push_back(b);
      continue;
    }
    for (int n = a; n <= b && n - a < 100; ++n) out.push_back(n);
  }
  return out;
}

const std::regex& EqsPattern() {
  // "eq 48", "eqs 41, 42, 47 and 57", "eqs 42-59" (a trailing "and N" included).
  static const std::regex kEqs(R"re(\beqs?\.? ?(\d+(?:\s*-\s*\d+)?(?:,\s*\d+(?:\s*-\s*\d+)?)*(?:,? and \d+)?))re");
  return kEqs;
}

struct ModelDoc {
  std::set<int> equations;
  std::set<int> sections;
};

ModelDoc ReadModelDoc() {
  ModelDoc doc;
  std::ifstream in(kRoot / "docs" / "model.md");
  static const std::regex kNumbered(R"re(\((\d+)\)\s*$)re");
  static const std::regex kSection(R"re(^## (\d+)\.)re");
  std::smatch m;
  for (std::string l; std::getline(in, l);) {
    if (std::regex_search(l, m, kNumbered)) doc.equations.insert(std::stoi(m[1].str()));
    if (std::regex_search(l, m, kSection)) {
      doc.sections.insert(std::stoi(m[1].str()));
      for (std::sregex_iterator it(l.begin(), l.end(), EqsPattern()), end; it != end; ++it) {
        for (int n : CitedNumbers((*it)[1].str(), true)) doc.equations.insert(n);
      }
    }
  }
  return doc;
}

std::vector<fs::path> Sources() {
  std::vector<fs::path> out;
  for (const char* d : {"src", "solvers", "apps", "python"}) {
    if (!fs::exists(kRoot / d)) continue;
    for (const auto& e : fs::recursive_directory_iterator(kRoot / d)) {
      const std::string ext = e.path().extension().string();
      if (e.is_regular_file() && (ext == ".h" || ext == ".cc" || ext == ".py")) out.push_back(e.path());
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(ModelCitationTest, EveryCitedEquationAndSectionIsInDocsModel) {
  const ModelDoc doc = ReadModelDoc();
  ASSERT_GE(doc.equations.size(), 40u) << "docs/model.md: its numbered equations were not found";
  ASSERT_GE(doc.sections.size(), 10u) << "docs/model.md: its numbered sections were not found";
  static const std::regex kSectionCite(R"re(model\.md,? sections? (\d+))re");
  int cited = 0;
  for (const fs::path& p : Sources()) {
    std::ifstream in(p);
    int line = 0;
    for (std::string l; std::getline(in, l);) {
      ++line;
      const std::string where = fs::relative(p, kRoot).string() + ":" + std::to_string(line);
      for (std::sregex_iterator it(l.begin(), l.end(), EqsPattern()), end; it != end; ++it) {
        for (int n : CitedNumbers((*it)[1].str(), false)) {
          ++cited;
          EXPECT_TRUE(doc.equations.count(n)) << where << " cites eq " << n << ", not in docs/model.md";
        }
      }
      for (std::sregex_iterator it(l.begin(), l.end(), kSectionCite), end; it != end; ++it) {
        ++cited;
        const int s = std::stoi((*it)[1].str());
        EXPECT_TRUE(doc.sections.count(s)) << where << " cites section " << s << ", not in docs/model.md";
      }
    }
  }
  EXPECT_GT(cited, 50) << "the code's citations of docs/model.md were not found";
}

}  // namespace

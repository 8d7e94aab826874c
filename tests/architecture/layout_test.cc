// The house rules a reviewer would otherwise check by hand, checked on the source tree itself:
//   - dependencies point one way: no include cycle between the folders of src/, and inside a
//     folder no include cycle between its modules (a module is x.h + x.cc);
//   - no source file over 1,200 lines and no function over 150 lines (src/, solvers/, apps/,
//     python/);
//   - every document of docs/ a comment cites is in the repository, and no comment points
//     outside it (to the shared folder's documents).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

const fs::path kRoot = DYNOSIZE_SOURCE_DIR;
constexpr std::size_t kMaxFileLines = 1200;      // issue's limit for one source file
constexpr std::size_t kMaxFunctionLines = 150;   // house rule for one function body

std::vector<std::string> ReadLines(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

bool IsSource(const fs::path& p) {
  const std::string e = p.extension().string();
  return e == ".h" || e == ".cc";
}

std::vector<fs::path> SourcesUnder(const std::vector<std::string>& dirs) {
  std::vector<fs::path> out;
  for (const std::string& d : dirs) {
    if (!fs::exists(kRoot / d)) continue;
    for (const auto& e : fs::recursive_directory_iterator(kRoot / d)) {
      if (e.is_regular_file() && IsSource(e.path())) out.push_back(e.path());
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The quoted includes of a file ("model/drive.h").
std::vector<std::string> QuotedIncludes(const fs::path& p) {
  static const std::regex kInclude(R"re(^\s*#\s*include\s+"([^"]+)")re");
  std::vector<std::string> out;
  std::smatch m;
  for (const std::string& l : ReadLines(p)) {
    if (std::regex_search(l, m, kInclude)) out.push_back(m[1].str());
  }
  return out;
}

using Graph = std::map<std::string, std::set<std::string>>;

// One cycle of the graph as "a -> b -> a", or "" when it has none.
std::string FindCycle(const Graph& g) {
  std::map<std::string, int> state;  // 0 new, 1 on the stack, 2 done
  std::vector<std::string> stack;
  std::string cycle;
  std::function<bool(const std::string&)> visit = [&](const std::string& n) {
    state[n] = 1;
    stack.push_back(n);
    const auto it = g.find(n);
    if (it != g.end()) {
      for (const std::string& m : it->second) {
        if (state[m] == 1) {
          auto from = std::find(stack.begin(), stack.end(), m);
          for (auto s = from; s != stack.end(); ++s) cycle += *s + " -> ";
          cycle += m;
          return true;
        }
        if (state[m] == 0 && visit(m)) return true;
      }
    }
    stack.pop_back();
    state[n] = 2;
    return false;
  };
  for (const auto& [node, edges] : g) {
    (void)edges;
    if (state[node] == 0 && visit(node)) return cycle;
  }
  return "";
}

TEST(LayoutTest, NoIncludeCycleBetweenFoldersOfSrc) {
  Graph folders;
  for (const fs::path& p : SourcesUnder({"src"})) {
    const std::string folder = fs::relative(p, kRoot / "src").begin()->string();
    for (const std::string& inc : QuotedIncludes(p)) {
      const auto slash = inc.find('/');
      if (slash == std::string::npos || !fs::exists(kRoot / "src" / inc)) continue;
      const std::string to = inc.substr(0, slash);
      if (to != folder) folders[folder].insert(to);
    }
  }
  EXPECT_EQ(FindCycle(folders), "") << "the folders of src/ include each other in a cycle";
}

TEST(LayoutTest, NoIncludeCycleBetweenModulesOfAFolder) {
  std::map<std::string, Graph> per_folder;  // folder -> module -> modules it includes
  for (const fs::path& p : SourcesUnder({"src"})) {
    const fs::path rel = fs::relative(p, kRoot / "src");
    const std::string folder = rel.parent_path().string();
    const std::string module = rel.stem().string();
    per_folder[folder][module];
    for (const std::string& inc : QuotedIncludes(p)) {
      const fs::path ip(inc);
      if (ip.parent_path().string() != folder || !fs::exists(kRoot / "src" / inc)) continue;
      const std::string to = ip.stem().string();
      if (to != module) per_folder[folder][module].insert(to);
    }
  }
  for (const auto& [folder, g] : per_folder) {
    EXPECT_EQ(FindCycle(g), "") << "src/" << folder << ": an include points up (a module cycle)";
  }
}

TEST(LayoutTest, NoSourceFileOverTheLimit) {
  for (const fs::path& p : SourcesUnder({"src", "solvers", "apps", "python", "tests", "bench", "fuzz"})) {
    EXPECT_LE(ReadLines(p).size(), kMaxFileLines) << fs::relative(p, kRoot).string();
  }
}

// A function's signature starts at column 0 and may go on over indented lines; its body opens at
// the end of the signature's last line and closes with "}" at column 0 (the code's format).
// Namespaces, classes, structs, enums and initialised data are not functions.
TEST(LayoutTest, NoFunctionOverTheLimit) {
  static const std::regex kBlock(R"re(^(namespace|class|struct|enum|extern|union)\b)re");
  for (const fs::path& p : SourcesUnder({"src", "solvers", "apps", "python"})) {
    const std::vector<std::string> lines = ReadLines(p);
    bool pending = false, in_function = false;
    std::size_t signature = 0, start = 0;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      const std::string& l = lines[i];
      if (in_function) {
        if (l.rfind("}", 0) == 0) {
          in_function = false;
          EXPECT_LE(i - start, kMaxFunctionLines) << fs::relative(p, kRoot).string() << ":" << signature + 1;
        }
        continue;
      }
      if (l.empty() || l.rfind("//", 0) == 0 || l[0] == '#') continue;
      if (l[0] != ' ' && l[0] != '\t') {
        const bool data = l.find('=') != std::string::npos && l.find("operator") == std::string::npos;
        if (l[0] == '}' || std::regex_search(l, kBlock) || data) {
          pending = false;
          continue;
        }
        if (!pending) signature = i;
        pending = pending || l.find('(') != std::string::npos || l.rfind("template", 0) == 0;
      }
      if (!pending) continue;
      if (l.back() == '{') {
        in_function = true;
        pending = false;
        start = i;
      } else if (l.back() == ';' || l.back() == '}') {
        pending = false;
      }
    }
  }
}

TEST(LayoutTest, EveryCitedDocumentIsInTheRepository) {
  const std::string kOutside = std::string("shared/") + "docs";  // not written whole: this file
  static const std::regex kDoc(R"re(\bdocs/([A-Za-z0-9_\-]+\.md))re");
  for (const fs::path& p : SourcesUnder({"src", "solvers", "apps", "python", "tests", "bench", "fuzz"})) {
    const std::vector<std::string> lines = ReadLines(p);
    for (std::size_t i = 0; i < lines.size(); ++i) {
      EXPECT_EQ(lines[i].find(kOutside), std::string::npos)
          << fs::relative(p, kRoot).string() << ":" << i + 1 << " points outside the repository";
      for (std::sregex_iterator it(lines[i].begin(), lines[i].end(), kDoc), end; it != end; ++it) {
        EXPECT_TRUE(fs::exists(kRoot / "docs" / (*it)[1].str()))
            << fs::relative(p, kRoot).string() << ":" << i + 1 << " cites docs/" << (*it)[1].str();
      }
    }
  }
}

}  // namespace

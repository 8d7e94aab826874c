#include "report/gnuplot.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "common/error.h"
#include "common/text_file.h"

namespace dynosize {

std::string FormatDataBlock(const DataBlock& block) {
  std::ostringstream out;
  out.precision(9);
  out << "$" << block.name << " << EOD\n";
  for (std::size_t s = 0; s < block.series.size(); ++s) {
    if (s > 0) out << (block.grid ? "\n" : "\n\n");
    const auto& cols = block.series[s];
    const std::size_t rows = cols.empty() ? 0 : cols[0].size();
    for (std::size_t r = 0; r < rows; ++r) {
      for (std::size_t c = 0; c < cols.size(); ++c) {
        const double v = cols[c][r];
        if (c) out << ' ';
        if (std::isfinite(v)) out << v; else out << "NaN";
      }
      out << '\n';
    }
  }
  out << "EOD\n";
  return out.str();
}

namespace {

std::string Quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'') q += "''"; else q += c;
  }
  return q + "'";
}

std::string ShellQuote(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'') q += "'\\''"; else q += c;
  }
  return q + "'";
}

}  // namespace

void RenderPng(const std::string& png_path, const std::vector<DataBlock>& blocks,
               const std::string& script_body, int width_px, int height_px) {
  namespace fs = std::filesystem;
  const fs::path png(png_path);
  const fs::path script_path = fs::path(png).replace_extension(".gp");
  // The process id keeps concurrent runs drawing into one folder off each other's file.
  const std::string tmp_png = (png.parent_path() / ("." + png.filename().string() + ".tmp-" +
                                                    std::to_string(::getpid()))).string();

  std::ostringstream script;
  script << "# Written by dynosize; run 'gnuplot " << script_path.filename().string()
         << "' to redraw.\n";
  for (const auto& b : blocks) script << FormatDataBlock(b);
  script << "set terminal pngcairo size " << width_px << "," << height_px
         << " font 'DejaVu Sans,11' noenhanced\n";
  // The kept script writes the final name; dynosize itself passes a temporary one.
  script << "if (!exists('outfile')) outfile = " << Quote(png.filename().string()) << "\n";
  script << "set output outfile\n";
  script << "set encoding utf8\nset grid lc rgb '#dddddd'\nset key outside right top\n";
  script << script_body << "\nunset output\n";
  WriteFileAtomic(script_path.string(), script.str());

  // Render into a temporary file, then rename it into place: a failed run leaves any earlier
  // figure intact.
  const std::string tmp_name = fs::path(tmp_png).filename().string();
  const std::string cmd =
      "cd " + ShellQuote(png.parent_path().empty() ? "." : png.parent_path().string()) +
      " && gnuplot -e " + ShellQuote("outfile='" + tmp_name + "'") + " " +
      ShellQuote(script_path.filename().string()) + " > /dev/null 2> " +
      ShellQuote(tmp_name + ".log") + " && mv -f " + ShellQuote(tmp_name) + " " +
      ShellQuote(png.filename().string());
  const int status = std::system(cmd.c_str());
  std::string log;
  try {
    log = ReadTextFile(tmp_png + ".log", 1u << 20);
  } catch (const Error&) {
  }
  std::remove((tmp_png + ".log").c_str());
  if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) {
      throw CantCreateError(png_path + ": gnuplot is not installed (apt-get install gnuplot-nox)");
    }
    throw CantCreateError(png_path + ": gnuplot failed: " + log.substr(0, 400));
  }
}

}  // namespace dynosize

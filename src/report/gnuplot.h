// Rendering figures with gnuplot (Debian package gnuplot-nox, pngcairo terminal).
//
// A figure is a gnuplot script whose data travel inline as datablocks ($name << EOD), so that
// one script file reproduces the figure. The PNG is written to a temporary name and renamed
// into place; the script is kept beside it (same name, .gp) for users who want to restyle.
#pragma once

#include <string>
#include <vector>

namespace dynosize {

// One inline datablock: rows of equal-length columns, separated by blank lines between
// `series` (gnuplot's "index" blocks) when more than one series is given.
struct DataBlock {
  std::string name;  // without the leading '$'
  // series -> columns -> values; every column in a series has the same length. Non-finite
  // values are written as NaN, which gnuplot treats as missing.
  std::vector<std::vector<std::vector<double>>> series;
  // false: series separated by two blank lines (gnuplot "index" blocks, one line per series);
  // true: by one blank line (scan lines of a grid for splot/pm3d).
  bool grid = false;
};

// Returns the datablock text "$name << EOD ... EOD\n".
std::string FormatDataBlock(const DataBlock& block);

// Writes `script_body` (everything after the terminal/output lines) preceded by the datablocks
// and a pngcairo terminal of the given size to `png_path` (via a temporary file) and keeps the
// script as png_path with extension .gp. Throws CantCreateError when gnuplot is missing or fails.
void RenderPng(const std::string& png_path, const std::vector<DataBlock>& blocks,
               const std::string& script_body, int width_px = 1000, int height_px = 700);

}  // namespace dynosize

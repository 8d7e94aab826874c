#include "logs/table_ops.h"

#include "common/error.h"

namespace dynosize::logs {

SteadyTable SelectRows(const SteadyTable& t, const std::vector<std::size_t>& keep) {
  SteadyTable out = t;
  for (int c = 0; c < kColumnCount; ++c) {
    auto& col = out.columns[c];
    col.clear();
    if (!t.info[c].present) continue;
    for (std::size_t i : keep) col.push_back(t.columns[c][i]);
  }
  out.source_line.clear();
  out.samples.clear();
  for (std::size_t i : keep) {
    out.source_line.push_back(t.source_line[i]);
    out.samples.push_back(i < t.samples.size() ? t.samples[i] : 1);
  }
  return out;
}

SteadyTable MergeLogs(const std::vector<SteadyTable>& tables) {
  if (tables.empty()) throw UsageError("no log to calibrate");
  if (tables.size() == 1) return tables[0];
  SteadyTable out = tables[0];
  for (std::size_t k = 1; k < tables.size(); ++k) {
    const SteadyTable& t = tables[k];
    out.file += ", " + t.file;
    for (int c = 0; c < kColumnCount; ++c) {
      if (!out.info[c].present) continue;
      if (!t.info[c].present) {
        out.info[c].present = false;
        out.info[c].note = std::string("absent from ") + t.file;
        out.columns[c].clear();
        continue;
      }
      out.columns[c].insert(out.columns[c].end(), t.columns[c].begin(), t.columns[c].end());
    }
    out.source_line.insert(out.source_line.end(), t.source_line.begin(), t.source_line.end());
    for (std::size_t i = 0; i < t.rows(); ++i) out.samples.push_back(i < t.samples.size() ? t.samples[i] : 1);
    for (const auto& d : t.dropped) AddDrop(&out, d.reason, d.count);
  }
  return out;
}

}  // namespace dynosize::logs

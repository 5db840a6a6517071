#ifndef FCL_SUPERELLIPSOID_BENCH_REPORT_H
#define FCL_SUPERELLIPSOID_BENCH_REPORT_H

// The benchmark's output: tables on the terminal, CSV and JSON of every row.

#include <cstdio>
#include <string>
#include <vector>

#include "accuracy_time.h"

namespace fcl_superellipsoid {
namespace bench {

/// The paper's Tables 1–4 layout (its 7 shapes, the +0.05 and −0.015 sides): Radial,
/// Paper 1e-3, Exact 1e-9 and 1e-12, FCL mesh 272 v; the paper's Implicit and mesh values
/// beside ours. Errors in mm (the shapes have radius 1 m, as in the paper).
void printPaperTables(const std::vector<Row>& rows, std::FILE* out);

/// Accuracy against time per side: every (method, setting) over all shapes, errors relative
/// to the shape's size, geometric-mean time, speedup against FCL's 272-vertex mesh.
void printSummary(const std::vector<Row>& rows, std::FILE* out);

/// Per shape and side: Exact (1e-12) speedup against FCL mesh 272 v, and the time ratio
/// Exact 1e-9 / Paper 1e-3 (the solver issue's speed target: ≤ 1).
void printSpeedRatios(const std::vector<Row>& rows, std::FILE* out);

/// The CSV header; one line per row (RFC 4180: text fields quoted).
std::string csvHeader();
void writeCsv(const std::vector<Row>& rows, const std::string& path);

/// {"meta": {...}, "rows": [{...}, ...]}, the same fields as the CSV.
void writeJson(const std::vector<Row>& rows, const RunConfig& config, const std::string& path);

/// CPU model and core count, for the output's header.
std::string machineDescription();

}  // namespace bench
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_BENCH_REPORT_H

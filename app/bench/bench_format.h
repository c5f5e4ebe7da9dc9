// Formatting shared by the bench report writers (bench_report.cpp, bench_methods_report.cpp):
// numbers for tables, CSV fields, and the per-pass timings in JSON and CSV.
#pragma once
#include <nlohmann/json.hpp>

#include <ostream>
#include <string>
#include <vector>

#include "app/bench/bench_report.h"

namespace gb {

std::string num(double v, int digits = 3);  // `digits` significant digits
std::string csvField(const std::string& s);  // quoted when it holds a comma, quote or newline
nlohmann::json timingJson(const Timing& t);  // {median, min, max}
// [{name, skipped, reason | ms: {median, min, max}}] in pass order.
nlohmann::json passesJson(const std::vector<PassTiming>& passes);
// Appends the names of `passes` that `names` lacks, in order: the CSV's pass columns.
void collectPassNames(const std::vector<PassTiming>& passes, std::vector<std::string>& names);
// One cell per name in `names`: ",median ms", or "," where the pass was skipped or absent.
void writePassCells(std::ostream& out, const std::vector<PassTiming>& passes, const std::vector<std::string>& names);

}  // namespace gb

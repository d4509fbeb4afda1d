#pragma once
// What the benchmarks share for their tables and JSON: clocks, number formats, the build they
// ran in, and an early check of the JSON output's folder.

#include <chrono>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "primo/solve/deformer.h"

namespace primo::bench {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start);

// "optimized (NDEBUG)", or in a debug build "debug (assertions on): <figures> are not
// representative".
std::string build_label(const std::string& figures = "figures");

// 12345.6 -> "12,346".
std::string with_thousands(double value);

// A solve's iterations, energies, time and how it stopped.
nlohmann::json report_json(const SolveReport& report);

double median_of(std::vector<double> values);

// Throws primo::Error when `json_path` is set and its folder does not exist: fails before
// minutes of measuring rather than after them.
void check_json_folder(const std::string& json_path);

}  // namespace primo::bench

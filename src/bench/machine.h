#pragma once
// The machine a benchmark ran on, as its tables and JSON describe it.

#include <string>
#include <vector>

namespace primo::bench {

// /proc/cpuinfo's model name, or "unknown".
std::string cpu_model();

// The BLAS and LAPACK libraries mapped into the process. CHOLMOD loads its BLAS dynamically
// through the system's alternatives, so the only cheap way to tell which one runs is to look at
// what is mapped after a solve.
std::vector<std::string> mapped_blas_libraries();

// The 1, 5 and 15 minute load averages (-1 each when unknown).
std::vector<double> load_average();

// The process's peak resident memory so far (ru_maxrss), in MB.
double peak_memory_mb();

}  // namespace primo::bench

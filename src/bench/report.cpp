#include "report.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "primo/util/error.h"

namespace fs = std::filesystem;

namespace primo::bench {

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string build_label(const std::string& figures) {
#ifdef NDEBUG
  (void)figures;
  return "optimized (NDEBUG)";
#else
  return "debug (assertions on): " + figures + " are not representative";
#endif
}

std::string with_thousands(double value) {
  const long long n = std::llround(value);
  std::string digits = std::to_string(n < 0 ? -n : n);
  for (int i = int(digits.size()) - 3; i > 0; i -= 3) digits.insert(size_t(i), ",");
  return (n < 0 ? "-" : "") + digits;
}

nlohmann::json report_json(const SolveReport& r) {
  return {{"iterations", r.iterations},
          {"exact_newton_steps", r.exact_newton_steps},
          {"initial_energy", r.initial_energy},
          {"energy", r.energy},
          {"seconds", r.seconds},
          {"converged", r.converged},
          {"stop_reason", r.stop_reason}};
}

double median_of(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void check_json_folder(const std::string& json_path) {
  if (json_path.empty()) return;
  std::error_code ec;
  const fs::path folder = fs::absolute(fs::path(json_path)).parent_path();
  if (!fs::is_directory(folder, ec))
    throw Error(json_path + ": the folder " + folder.string() + " does not exist");
}

}  // namespace primo::bench

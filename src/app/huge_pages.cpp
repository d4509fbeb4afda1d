#include "huge_pages.h"

#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <string>

namespace primo::app {
namespace {

constexpr const char* kTunable = "glibc.malloc.hugetlb=";

}  // namespace

void restart_with_huge_pages(char** argv) {
  const char* wanted = std::getenv("PRIMO_HUGE_PAGES");
  if (wanted && std::string(wanted) == "0") return;
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  // Set already (by an earlier start of ours, or by the user either way): leave it.
  if (tunables && std::strstr(tunables, kTunable)) return;
  std::string value = std::string(kTunable) + "1";
  if (tunables && *tunables) value = std::string(tunables) + ":" + value;
  if (setenv("GLIBC_TUNABLES", value.c_str(), 1) != 0) return;
  execv("/proc/self/exe", argv);
  // Not replaced (no /proc, say): run as we are, with the environment as it was.
  if (tunables) {
    setenv("GLIBC_TUNABLES", tunables, 1);
  } else {
    unsetenv("GLIBC_TUNABLES");
  }
}

}  // namespace primo::app

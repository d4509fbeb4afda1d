// `primo bench engine --quick`: runs headless and reports every figure it promises.

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>

#include "test_support.h"

TEST(BenchCli, EngineReportsItsFigures) {
  const std::string dir = primo::test::temp_dir();
  const std::string command = std::string(PRIMO_EXECUTABLE) + " bench engine --quick --json " +
                              dir + "/bench.json > " + dir + "/out.txt 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::ifstream in(dir + "/bench.json");
  const nlohmann::json bench = nlohmann::json::parse(in);
  EXPECT_GT(bench["local"]["matches_per_second"].get<double>(), 0.0);
  EXPECT_GT(bench["global"]["updates_per_second"].get<double>(), 0.0);
  // Local sweeps only ever lower the energy.
  EXPECT_LT(bench["local"]["energy_after_sweeps"].get<double>(),
            bench["local"]["initial_energy"].get<double>());
  ASSERT_EQ(bench["convergence"].size(), 4u);
  for (const auto& run : bench["convergence"]) {
    EXPECT_GT(run["iterations"].get<int>(), 0);
    EXPECT_LT(run["energy"].get<double>(), run["initial_energy"].get<double>());
  }
  EXPECT_GE(bench["machine"]["hardware_threads"].get<int>(), 1);
  EXPECT_TRUE(bench["real_mesh"].contains("skipped"));  // --quick skips the real mesh
}

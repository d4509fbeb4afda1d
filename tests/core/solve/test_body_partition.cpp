// Parts and colours for sweeps on every core: every body in one part, parts of one colour never
// coupled, and the result a function of the positions and pairs alone.

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "primo/solve/body_partition.h"

using namespace primo;

namespace {

// A grid of bodies, each coupled to its right and upper neighbours: rows of equal height tie
// along that axis, as a cylinder's rings do.
struct Grid {
  std::vector<Vec3> position;
  std::vector<std::pair<int, int>> edges;
};

Grid grid(int columns, int rows) {
  Grid g;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) g.position.emplace_back(double(c), 0.5 * double(r), 0.0);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) {
      const int b = r * columns + c;
      if (c + 1 < columns) g.edges.emplace_back(b, b + 1);
      if (r + 1 < rows) g.edges.emplace_back(b, b + columns);
    }
  return g;
}

std::vector<int> all_of(size_t n) {
  std::vector<int> all(n);
  std::iota(all.begin(), all.end(), 0);
  return all;
}

}  // namespace

TEST(BodyPartition, EveryBodyInOnePartAndNoColourCoupled) {
  const Grid g = grid(100, 90);
  const BodyPartition partition =
      partition_bodies(all_of(g.position.size()), g.position, g.edges, 500);
  ASSERT_EQ(partition.parts.size(), 16u);  // 9,000 bodies at 500 a part: four bisections
  std::vector<int> part_of(g.position.size(), -1);
  for (size_t p = 0; p < partition.parts.size(); ++p) {
    const std::vector<int>& part = partition.parts[p];
    EXPECT_TRUE(std::is_sorted(part.begin(), part.end()));
    EXPECT_NEAR(double(part.size()), 9000.0 / 16.0, 1.0);
    for (int b : part) {
      ASSERT_EQ(part_of[size_t(b)], -1) << "body " << b << " in two parts";
      part_of[size_t(b)] = int(p);
    }
  }
  EXPECT_EQ(std::count(part_of.begin(), part_of.end(), -1), 0);
  std::vector<int> colour_of(partition.parts.size(), -1);
  for (size_t c = 0; c < partition.colours.size(); ++c)
    for (int p : partition.colours[c]) colour_of[size_t(p)] = int(c);
  EXPECT_EQ(std::count(colour_of.begin(), colour_of.end(), -1), 0);
  for (const auto& [a, b] : g.edges) {
    const int pa = part_of[size_t(a)], pb = part_of[size_t(b)];
    if (pa != pb) EXPECT_NE(colour_of[size_t(pa)], colour_of[size_t(pb)]) << a << "-" << b;
  }
  EXPECT_GT(partition.colours.size(), 1u);
}

TEST(BodyPartition, PairsWithANegativeEndAreIgnored) {
  // A coupling to a body that does not move comes as (-1, -1) (the Hessian's pairs): it
  // colours nothing, and is never used as an index.
  const Grid g = grid(60, 40);
  std::vector<std::pair<int, int>> with_fixed = g.edges;
  for (int k = 0; k < 50; ++k) with_fixed.insert(with_fixed.begin() + 7 * k, {-1, -1});
  const BodyPartition plain = partition_bodies(all_of(g.position.size()), g.position, g.edges, 300);
  const BodyPartition fixed =
      partition_bodies(all_of(g.position.size()), g.position, with_fixed, 300);
  EXPECT_EQ(fixed.parts, plain.parts);
  EXPECT_EQ(fixed.colours, plain.colours);
}

TEST(BodyPartition, RenumberedBodiesGiveTheSamePartsRenumbered) {
  // Bodies numbered part after part (the multigrid's rows), with ties along the bisected axes:
  // the same parts come out, as runs of the new numbers, with the same colours.
  const Grid g = grid(80, 75);
  const BodyPartition by_body =
      partition_bodies(all_of(g.position.size()), g.position, g.edges, 400);
  std::vector<int> body_of_row, row_of_body(g.position.size());
  for (const std::vector<int>& part : by_body.parts)
    for (int b : part) {
      row_of_body[size_t(b)] = int(body_of_row.size());
      body_of_row.push_back(b);
    }
  ASSERT_NE(body_of_row, all_of(g.position.size()));  // a real renumbering
  std::vector<Vec3> row_position;
  for (int b : body_of_row) row_position.push_back(g.position[size_t(b)]);
  std::vector<std::pair<int, int>> row_edges;
  for (const auto& [a, b] : g.edges)
    row_edges.emplace_back(row_of_body[size_t(a)], row_of_body[size_t(b)]);
  const BodyPartition by_row =
      partition_bodies(all_of(g.position.size()), row_position, row_edges, 400);
  ASSERT_EQ(by_row.parts.size(), by_body.parts.size());
  int next = 0;
  for (const std::vector<int>& part : by_row.parts)
    for (int row : part) EXPECT_EQ(row, next++);
  for (size_t p = 0; p < by_row.parts.size(); ++p)
    EXPECT_EQ(by_row.parts[p].size(), by_body.parts[p].size());
  EXPECT_EQ(by_row.colours, by_body.colours);
}

// The workspace grid: cell centres, nearest cells and lattices, by hand.
#include <gtest/gtest.h>

#include "touchcloud/error.hpp"
#include "touchcloud/types/workspace.hpp"

using namespace touchcloud;

namespace {
WorkspaceGrid fox_like() {
  WorkspaceGrid g;
  g.x_mm = {0, 140};
  g.y_mm = {-70, 70};
  g.cells_x = 14;
  g.cells_y = 14;
  return g;
}
}  // namespace

TEST(WorkspaceGrid, CellCentresAreRowMajor) {
  const WorkspaceGrid g = fox_like();
  EXPECT_EQ(g.cells(), 196);
  EXPECT_TRUE(g.cell_centre_mm(0).isApprox(Eigen::Vector2d(5, -65)));
  EXPECT_TRUE(g.cell_centre_mm(13).isApprox(Eigen::Vector2d(135, -65)));
  EXPECT_TRUE(g.cell_centre_mm(14).isApprox(Eigen::Vector2d(5, -55)));
  EXPECT_EQ(g.cell_centres_mm().rows(), 196);
}

TEST(WorkspaceGrid, NearestCellRoundTripsAndClamps) {
  const WorkspaceGrid g = fox_like();
  for (int c = 0; c < g.cells(); ++c) EXPECT_EQ(g.nearest_cell(g.cell_centre_mm(c)), c);
  EXPECT_EQ(g.nearest_cell({-500, -500}), 0);
  EXPECT_EQ(g.nearest_cell({500, 500}), 195);
  EXPECT_EQ(g.nearest_cell({9.9, -60.1}), 0);
}

TEST(WorkspaceGrid, LatticeIncludesTheCorners) {
  const Eigen::MatrixX2d l = fox_like().lattice_mm(3, 2);
  ASSERT_EQ(l.rows(), 6);
  EXPECT_TRUE(l.row(0).isApprox(Eigen::RowVector2d(0, -70)));
  EXPECT_TRUE(l.row(1).isApprox(Eigen::RowVector2d(70, -70)));
  EXPECT_TRUE(l.row(5).isApprox(Eigen::RowVector2d(140, 70)));
}

TEST(WorkspaceGrid, EmptyWorkspaceNamesTheParameter) {
  WorkspaceGrid g = fox_like();
  g.y_mm = {5, 5};
  try {
    g.validate("wx", "wy", "cells");
    FAIL();
  } catch (const ParameterError& e) {
    EXPECT_EQ(e.parameter(), "wy");
  }
}

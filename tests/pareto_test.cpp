// The sweep's Pareto front and budget choice on a hand-made set of (time, error) points.
#include "tool/pareto.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace softstep::tool {
namespace {

const std::vector<CostPoint> kPoints{
    {1.0, 10.0},                                      // 0 front
    {2.0, 5.0},                                       // 1 front
    {3.0, 7.0},                                       // 2 beaten by 1 on both
    {4.0, 1.0},                                       // 3 front
    {0.5, 20.0},                                      // 4 front: the fastest
    {5.0, 1.0},                                       // 5 as accurate as 3, slower
    {4.0, 3.0},                                       // 6 as fast as 3, less accurate
    {2.0, 5.0},                                       // 7 equal to 1: both stay
    {6.0, std::numeric_limits<double>::quiet_NaN()},  // 8 blew up
    {0.1, std::numeric_limits<double>::infinity()},   // 9 blew up, fastest of all
};

TEST(Pareto, FrontOfAHandMadeSet) {
  const std::vector<bool> front = pareto_front(kPoints);
  const std::vector<bool> expected{true, true, false, true, true, false, false, true, false, false};
  EXPECT_EQ(front, expected);
}

TEST(Pareto, MostAccurateWithinABudget) {
  EXPECT_EQ(most_accurate_within(kPoints, 0.2), -1);  // only the blown-up run is that fast
  EXPECT_EQ(most_accurate_within(kPoints, 0.5), 4);
  EXPECT_EQ(most_accurate_within(kPoints, 3.5), 1);  // 1 and 7 tie: the first
  EXPECT_EQ(most_accurate_within(kPoints, 4.0), 3);
  EXPECT_EQ(most_accurate_within(kPoints, 100.0), 3);  // 5 ties 3 on error but is slower
}

}  // namespace
}  // namespace softstep::tool

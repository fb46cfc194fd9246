// Declared parameters: binding to members, rules, and the messages they give.
#include <gtest/gtest.h>

#include "touchcloud/error.hpp"
#include "touchcloud/parameters.hpp"

using namespace touchcloud;

namespace {
struct Members {
  double leaf = 0;
  int count = 0;
  unsigned small = 0;
  std::string method;
  std::vector<double> normal;
  bool flag = false;
};

ParameterSet declare(Members& m) {
  ParameterSet p;
  p.add("leaf_size_mm", m.leaf, 1.5).unit("mm").above(0.0).doc("voxel edge");
  p.add("count", m.count, 10).range(1, 100).doc("how many");
  p.add("small", m.small, 3u).doc("an unsigned member");
  p.add("method", m.method, std::string("voxel")).choices({"voxel", "random"}).doc("which");
  p.add("normal", m.normal, std::vector<double>{0, 0, 1}).size(3).range(-1, 1).doc("plate normal");
  p.add("flag", m.flag, true).doc("switch");
  return p;
}
}  // namespace

TEST(Parameters, DeclarationSetsDefaultsInMembers) {
  Members m;
  ParameterSet p = declare(m);
  EXPECT_EQ(m.leaf, 1.5);
  EXPECT_EQ(m.count, 10);
  EXPECT_EQ(m.method, "voxel");
  EXPECT_EQ(m.normal, (std::vector<double>{0, 0, 1}));
  EXPECT_TRUE(m.flag);
  ASSERT_EQ(p.specs().size(), 6u);
  EXPECT_EQ(p.find("leaf_size_mm")->unit, "mm");
}

TEST(Parameters, AssignStoresInBoundMember) {
  Members m;
  ParameterSet p = declare(m);
  p.assign("leaf_size_mm", 2.25);
  p.assign("count", std::int64_t{42});
  p.assign("method", std::string("random"));
  p.assign("normal", std::vector<double>{0.1, 0.0, 0.99});
  EXPECT_EQ(m.leaf, 2.25);
  EXPECT_EQ(m.count, 42);
  EXPECT_EQ(m.method, "random");
  EXPECT_DOUBLE_EQ(m.normal[2], 0.99);
  p.assign_defaults();
  EXPECT_EQ(m.leaf, 1.5);
  EXPECT_EQ(m.method, "voxel");
}

TEST(Parameters, ViolationsNameTheRuleAndUnit) {
  Members m;
  ParameterSet p = declare(m);
  try {
    p.assign("leaf_size_mm", -1.0);
    FAIL() << "negative leaf accepted";
  } catch (const ParameterError& e) {
    EXPECT_EQ(e.parameter(), "leaf_size_mm");
    EXPECT_NE(e.detail().find("must be > 0 (mm)"), std::string::npos) << e.detail();
  }
  EXPECT_EQ(m.leaf, 1.5) << "a rejected value must not reach the member";
  EXPECT_THROW(p.assign("count", std::int64_t{101}), ParameterError);
  EXPECT_THROW(p.assign("count", 5.0), ParameterError);  // wrong type
  EXPECT_THROW(p.assign("method", std::string("octree")), ParameterError);
  EXPECT_THROW(p.assign("normal", std::vector<double>{0, 1}), ParameterError);
  EXPECT_THROW(p.assign("normal", std::vector<double>{0, 2, 0}), ParameterError);
  EXPECT_THROW(p.assign("nope", 1.0), ParameterError);
}

TEST(Parameters, NonFiniteNumbersAreRejected) {
  Members m;
  ParameterSet p = declare(m);
  EXPECT_THROW(p.assign("leaf_size_mm", std::numeric_limits<double>::quiet_NaN()), ParameterError);
  EXPECT_THROW(p.assign("leaf_size_mm", std::numeric_limits<double>::infinity()), ParameterError);
  EXPECT_EQ(m.leaf, 1.5);
}

TEST(Parameters, IntegerMembersKeepTheirOwnLimits) {
  Members m;
  ParameterSet p = declare(m);
  EXPECT_THROW(p.assign("small", std::int64_t{-1}), ParameterError);  // unsigned member
  p.assign("small", std::int64_t{7});
  EXPECT_EQ(m.small, 7u);
}

TEST(Parameters, RulesReadAsWords) {
  Members m;
  ParameterSet p = declare(m);
  EXPECT_EQ(p.find("leaf_size_mm")->rule(), "> 0");
  EXPECT_EQ(p.find("count")->rule(), "in [1, 100]");
  EXPECT_EQ(p.find("method")->rule(), "one of: voxel, random");
  EXPECT_EQ(p.find("normal")->rule(), "3 values, each in [-1, 1]");
}

TEST(Parameters, DeclaringANameTwiceIsAProgrammingError) {
  double a = 0, b = 0;
  ParameterSet p;
  p.add("x", a, 1.0);
  EXPECT_THROW(p.add("x", b, 2.0), std::logic_error);
}

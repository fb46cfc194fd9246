// Declared parameters: binding to members, rules, and the messages they give.
#include <gtest/gtest.h>

#include "touchcloud/error.hpp"
#include "touchcloud/parameters.hpp"

#include <array>
#include <optional>

using namespace touchcloud;

namespace {
enum class Method { Voxel, Random };
struct Members {
  double leaf = 0;
  int count = 0;
  unsigned small = 0;
  Method method = Method::Random;
  std::vector<double> normal;
  bool flag = false;
};

ParameterSet declare(Members& m) {
  ParameterSet p;
  p.add("leaf_size_mm", m.leaf, 1.5).unit("mm").above(0.0).doc("voxel edge");
  p.add("count", m.count, 10).range(1, 100).doc("how many");
  p.add("small", m.small, 3u).doc("an unsigned member");
  p.add("method", m.method, Method::Voxel, {{"voxel", Method::Voxel}, {"random", Method::Random}}).doc("which");
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
  EXPECT_EQ(m.method, Method::Voxel);
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
  EXPECT_EQ(m.method, Method::Random);
  EXPECT_DOUBLE_EQ(m.normal[2], 0.99);
  EXPECT_TRUE(p.was_set("method"));
  EXPECT_FALSE(p.was_set("flag"));
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

TEST(Parameters, EnumChoicesAreDeclaredOnceAndAnUnknownNameReachesNoMember) {
  Members m;
  ParameterSet p = declare(m);
  EXPECT_EQ(p.find("method")->type, ParamType::Choice);
  EXPECT_EQ(p.find("method")->choices, (std::vector<std::string>{"voxel", "random"}));
  EXPECT_EQ(*p.find("method")->default_value, ParamValue(std::string("voxel")));
  try {
    p.assign("method", std::string("Random"));  // a typo of a choice
    FAIL() << "accepted";
  } catch (const ParameterError& e) {
    EXPECT_EQ(e.detail(), "value 'Random' is not allowed: must be one of: voxel, random");
  }
  EXPECT_EQ(m.method, Method::Voxel);
  EXPECT_EQ(p.current("method"), ParamValue(std::string("voxel")));
}

TEST(Parameters, IntegerListsAndPairsTakeWholeNumbersOnly) {
  std::vector<int> cells;
  std::array<int, 2> pair{};
  std::array<unsigned char, 2> bytes{};
  ParameterSet p;
  p.add("cells", cells, std::vector<int>{1, 2, 3}).at_least(1);
  p.add("pair", pair, std::array<int, 2>{14, 14}).range(1, 1000);
  p.add("bytes", bytes, std::array<unsigned char, 2>{1, 2});
  EXPECT_EQ(pair, (std::array<int, 2>{14, 14}));
  EXPECT_EQ(p.find("pair")->type, ParamType::IntList);
  EXPECT_EQ(p.find("pair")->rule(), "2 values, each in [1, 1000]");
  p.assign("pair", std::vector<std::int64_t>{24, 6});
  EXPECT_EQ(pair, (std::array<int, 2>{24, 6}));
  EXPECT_THROW(p.assign("pair", std::vector<double>{24.5, 6}), ParameterError);  // not whole
  EXPECT_THROW(p.assign("pair", std::vector<std::int64_t>{24}), ParameterError);  // not a pair
  EXPECT_THROW(p.assign("pair", std::vector<std::int64_t>{0, 6}), ParameterError);
  EXPECT_THROW(p.assign("bytes", std::vector<std::int64_t>{1, 256}), ParameterError);  // the member's own limit
  p.assign("cells", std::vector<std::int64_t>{5, 6, 7, 8});
  EXPECT_EQ(cells, (std::vector<int>{5, 6, 7, 8}));
  EXPECT_EQ(pair, (std::array<int, 2>{24, 6})) << "a refused value leaves the member as it was";
}

TEST(Parameters, AnOptionalParameterIsNotSetUntilSomethingSetsIt) {
  std::optional<double> speed = 3.0;
  std::optional<std::array<double, 2>> target;
  ParameterSet p;
  p.add("speed_mm_s", speed).above(0).unit("mm/s");
  p.add("target_xy_mm", target);
  EXPECT_FALSE(speed.has_value()) << "declaration makes it not set";
  EXPECT_FALSE(p.find("speed_mm_s")->default_value.has_value());
  EXPECT_TRUE(p.find("speed_mm_s")->optional);
  EXPECT_FALSE(p.current("speed_mm_s"));
  EXPECT_THROW(p.assign("speed_mm_s", -1.0), ParameterError) << "no sentinel: -1 is out of range";
  p.assign("speed_mm_s", 5.0);
  EXPECT_EQ(speed, 5.0);
  p.assign("target_xy_mm", std::vector<double>{1, 2});
  EXPECT_EQ(target, (std::array<double, 2>{1, 2}));
  p.unset("speed_mm_s");
  EXPECT_FALSE(speed.has_value());
  EXPECT_FALSE(p.was_set("speed_mm_s"));
  double plain = 0;
  p.add("plain", plain, 1.0);
  EXPECT_THROW(p.unset("plain"), ParameterError) << "only an optional parameter can be not set";
}

TEST(Parameters, RulesBetweenParametersBlameTheOneThePipelineSet) {
  double lo = 0, hi = 0;
  ParameterSet p;
  p.add("lo", lo, 1.0);
  p.add("hi", hi, 2.0);
  p.rule({"lo", "hi"}, [&]() -> std::optional<std::string> {
    if (lo < hi) return std::nullopt;
    return "must be below hi";
  });
  EXPECT_TRUE(p.broken_rules().empty());
  p.assign("hi", 0.5);
  const auto broken = p.broken_rules();
  ASSERT_EQ(broken.size(), 1u);
  EXPECT_EQ(broken[0].first, "hi");  // the value the pipeline set, not the default
  EXPECT_EQ(broken[0].second, "must be below hi");
  EXPECT_THROW(p.rule({"nope"}, [] { return std::optional<std::string>(); }), std::logic_error);
}

TEST(Parameters, AParameterOfAMissingBuildFeatureIsRefusedWhenSet) {
  std::optional<int> threads;
  ParameterSet p;
  p.add("blas_threads", threads).at_least(1).needs("OpenBLAS", false);
  try {
    p.assign("blas_threads", std::int64_t{2});
    FAIL() << "accepted";
  } catch (const ParameterError& e) {
    EXPECT_NE(e.detail().find("built without OpenBLAS"), std::string::npos) << e.detail();
  }
  EXPECT_FALSE(threads.has_value());
  std::optional<int> other;
  ParameterSet q;
  q.add("blas_threads", other).needs("OpenBLAS", true);
  q.assign("blas_threads", std::int64_t{2});
  EXPECT_EQ(other, 2);
}

TEST(Parameters, EveryDefaultIsCheckedAgainstItsOwnRule) {
  double leaf = 0;
  int count = 0;
  ParameterSet good;
  good.add("leaf_size_mm", leaf, 1.0).above(0);
  EXPECT_NO_THROW(good.check_defaults());
  ParameterSet bad;
  bad.add("count", count, 0).range(1, 10);
  try {
    bad.check_defaults();
    FAIL() << "a default outside its range passed";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("'count': its default breaks its own rule"), std::string::npos) << e.what();
  }
  Method method;
  ParameterSet missing;  // a default that is not among the choices
  missing.add("method", method, Method::Random, {{"voxel", Method::Voxel}});
  EXPECT_THROW(missing.check_defaults(), std::logic_error);
}

TEST(Parameters, NumbersPrintInTheShortestExactForm) {
  EXPECT_EQ(format_value(1e-300), "1e-300");
  EXPECT_EQ(format_value(0.1), "0.1");
  EXPECT_EQ(format_value(std::vector<std::int64_t>{14, 6}), "[14, 6]");
}

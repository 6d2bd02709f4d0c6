#include <gtest/gtest.h>

#include "imagenets/property.h"

using namespace imagenets;

TEST(Property, ParsesEachKind) {
  EXPECT_EQ(std::get<int>(PropertySpec("t", PropertyKind::Int, 0, "").parse("72")), 72);
  EXPECT_DOUBLE_EQ(std::get<double>(PropertySpec("s", PropertyKind::Double, 0.0, "").parse("1.5")), 1.5);
  EXPECT_TRUE(std::get<bool>(PropertySpec("b", PropertyKind::Bool, false, "").parse("true")));
  EXPECT_EQ(std::get<std::string>(PropertySpec("p", PropertyKind::String, std::string(), "").parse("a/b.png")),
            "a/b.png");
  auto list = std::get<std::vector<double>>(
      PropertySpec("l", PropertyKind::DoubleList, std::vector<double>{}, "").parse("[1, 2.5, -3]"));
  EXPECT_EQ(list, (std::vector<double>{1, 2.5, -3}));
}

TEST(Property, RejectsWrongTypeWithTheValue) {
  PropertySpec spec("threshold", PropertyKind::Int, 128, "");
  try {
    spec.parse("abc");
    FAIL() << "accepted abc";
  } catch (const PropertyError& e) {
    EXPECT_NE(std::string(e.what()).find("expected int"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'abc'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(spec.parse("1.5"), PropertyError);
  EXPECT_THROW(spec.parse("[1, 2]"), PropertyError);
}

TEST(Property, RejectsOutOfRangeWithTheRange) {
  PropertySpec spec("threshold", PropertyKind::Int, 128, "");
  spec.range(0, 255);
  try {
    spec.parse("300");
    FAIL() << "accepted 300";
  } catch (const PropertyError& e) {
    EXPECT_NE(std::string(e.what()).find("300 is out of range [0, 255]"), std::string::npos) << e.what();
  }
  EXPECT_EQ(std::get<int>(spec.parse("255")), 255);
}

TEST(Property, EnumerationsAcceptOnlyTheirChoices) {
  PropertySpec spec("mode", PropertyKind::String, std::string("a"), "");
  spec.choices({"a", "b"});
  EXPECT_EQ(spec.kind(), PropertyKind::Enum);
  EXPECT_EQ(std::get<std::string>(spec.parse("b")), "b");
  try {
    spec.parse("c");
    FAIL();
  } catch (const PropertyError& e) {
    EXPECT_NE(std::string(e.what()).find("not one of: a, b"), std::string::npos) << e.what();
  }
}

TEST(Property, FromNumberRoundsIntegers) {
  PropertySpec spec("t", PropertyKind::Int, 0, "");
  spec.range(0, 255);
  EXPECT_EQ(std::get<int>(spec.fromNumber(71.6)), 72);
  EXPECT_THROW(spec.fromNumber(300), PropertyError);
  EXPECT_THROW(PropertySpec("s", PropertyKind::String, std::string(), "").fromNumber(1), PropertyError);
}

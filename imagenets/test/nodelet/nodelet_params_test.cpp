// Property values from ROS parameters and dynamic_reconfigure requests: same checks and messages
// as net files; dicts become YAML text for string properties.
#include <gtest/gtest.h>

#include "imagenets/param_text.h"
#include "../../src/nodelet/reconfigure.h"

namespace imagenets {
namespace {

PropertySpec intSpec() {
  PropertySpec s("threshold", PropertyKind::Int, 128, "gray level");
  s.range(0, 255);
  return s;
}

// A parameter goes the one property-text path: its text, parsed by the spec.
PropertyValue parseParam(const PropertySpec& spec, const XmlRpc::XmlRpcValue& value) {
  return spec.parse(paramText(value));
}

TEST(NodeletParams, ScalarsAreCheckedLikeNetFileText) {
  EXPECT_EQ(std::get<int>(parseParam(intSpec(), XmlRpc::XmlRpcValue(72))), 72);
  EXPECT_EQ(std::get<int>(parseParam(intSpec(), XmlRpc::XmlRpcValue(std::string("72")))), 72);
  try {
    parseParam(intSpec(), XmlRpc::XmlRpcValue(300));
    FAIL();
  } catch (const PropertyError& e) {
    EXPECT_STREQ(e.what(), "value 300 is out of range [0, 255]");
  }
  EXPECT_THROW(parseParam(intSpec(), XmlRpc::XmlRpcValue(2.5)), PropertyError);
  PropertySpec d("sigma", PropertyKind::Double, 0.0, "");
  EXPECT_DOUBLE_EQ(std::get<double>(parseParam(d, XmlRpc::XmlRpcValue(2))), 2.0);
  PropertySpec b("invert", PropertyKind::Bool, false, "");
  EXPECT_TRUE(std::get<bool>(parseParam(b, XmlRpc::XmlRpcValue(true))));
}

TEST(NodeletParams, ListsAndDictsBecomeYaml) {
  PropertySpec list("weights", PropertyKind::DoubleList, std::vector<double>{}, "");
  XmlRpc::XmlRpcValue v;
  v[0] = 1;
  v[1] = 2.5;
  EXPECT_EQ(std::get<std::vector<double>>(parseParam(list, v)), (std::vector<double>{1.0, 2.5}));

  // A net written as a rosparam dict inside a launch file, given to a string property.
  XmlRpc::XmlRpcValue net;
  net["blocks"]["gray"]["type"] = std::string("imagenets/Grayscale");
  net["links"][0] = std::string("a.image -> gray.image");
  PropertySpec text("net_yaml", PropertyKind::String, std::string(), "");
  const std::string yaml = std::get<std::string>(parseParam(text, net));
  EXPECT_NE(yaml.find("gray:"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("type: imagenets/Grayscale"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("a.image -> gray.image"), std::string::npos) << yaml;
  // A string that looks like YAML stays the string it is.
  EXPECT_EQ(std::get<std::string>(parseParam(text, XmlRpc::XmlRpcValue(std::string("a: b")))), "a: b");
}

TEST(NodeletParams, ReconfigureDescriptionCarriesTypesRangesAndChoices) {
  PropertySpec threshold = intSpec();
  PropertySpec mode("mode", PropertyKind::String, std::string("exact"), "pairing");
  mode.choices({"exact", "approximate"});
  PropertySpec list("weights", PropertyKind::DoubleList, std::vector<double>{1.0}, "");
  auto d = describeProperties({&threshold, &mode, &list});
  ASSERT_EQ(d.groups.size(), 1u);
  ASSERT_EQ(d.groups[0].parameters.size(), 3u);
  EXPECT_EQ(d.groups[0].parameters[0].type, "int");
  EXPECT_EQ(d.groups[0].parameters[1].type, "str");
  EXPECT_NE(d.groups[0].parameters[1].edit_method.find("'name': 'approximate'"), std::string::npos);
  EXPECT_EQ(d.groups[0].parameters[2].type, "str");
  ASSERT_EQ(d.min.ints.size(), 1u);
  EXPECT_EQ(d.min.ints[0].value, 0);
  EXPECT_EQ(d.max.ints[0].value, 255);
  EXPECT_EQ(d.dflt.ints[0].value, 128);
  EXPECT_EQ(d.dflt.strs[1].value, "[1]");

  dynamic_reconfigure::Config request;
  dynamic_reconfigure::DoubleParameter p;
  p.name = "threshold";
  p.value = 72.0;  // a Python client may send a whole number as a double
  request.doubles.push_back(p);
  auto decoded = decodeRequest(request);
  ASSERT_EQ(decoded.size(), 1u);
  EXPECT_EQ(std::get<int>(threshold.parse(decoded[0].second)), 72);
  EXPECT_THROW(mode.parse("sideways"), PropertyError);
  EXPECT_EQ(std::get<std::vector<double>>(list.parse("[3, 4]")), (std::vector<double>{3, 4}));
}

}  // namespace
}  // namespace imagenets

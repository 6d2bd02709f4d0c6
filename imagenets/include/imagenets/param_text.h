// Property values from ROS parameters: an XmlRpc value becomes the text a net file would hold,
// so PropertySpec::parse (the one property-text path) checks it with the same messages. A dict or list given to a string
// property becomes YAML text (a net can be written inside a launch file, as a rosparam dict).
#pragma once

#include <string>

#include <xmlrpcpp/XmlRpcValue.h>

#include "imagenets/property.h"

namespace imagenets {

// YAML text of a parameter value (flow style for scalars and lists, block style for dicts).
std::string paramToYaml(XmlRpc::XmlRpcValue value);
// The text a net file would hold for a parameter: a string as it is, anything else as YAML.
std::string paramText(const XmlRpc::XmlRpcValue& value);
// The parameter to store for a property value (dynamic_reconfigure keeps the server's params current).
XmlRpc::XmlRpcValue propertyToParam(const PropertyValue& value);

}  // namespace imagenets

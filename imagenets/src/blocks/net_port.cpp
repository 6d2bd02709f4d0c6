#include "imagenets/net_port.h"

#include "imagenets/port_type.h"
#include "imagenets/property.h"

namespace imagenets {

const PortType& netPortType(const std::string& name) {
  const PortType* type = PortType::find(name);
  if (!type) {
    std::string known;
    for (const auto& n : PortType::names()) known += (known.empty() ? "" : ", ") + n;
    throw PropertyError("property 'type': unknown message type '" + name + "' (known: " + known + ")");
  }
  return *type;
}

}  // namespace imagenets

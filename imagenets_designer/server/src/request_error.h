// A request the Designer cannot serve: the text names what is wrong and where.
#pragma once

#include <stdexcept>

namespace imagenets {
namespace designer {

struct RequestError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace designer
}  // namespace imagenets

// The name under which a C++ type travels between stages. Data types give
// themselves a name where they are defined, without the pipeline runtime:
//
//   TOUCHCLOUD_DATA_TYPE(my::GelImage, "gel_image")
//
// Ports (touchcloud/ports.hpp) then accept the type by that name.
#pragma once

#include <string_view>

namespace touchcloud {

template <class T>
struct DataTypeName;  // specialised by TOUCHCLOUD_DATA_TYPE

}  // namespace touchcloud

#define TOUCHCLOUD_DATA_TYPE(CXX_TYPE, NAME)                  \
  template <>                                                 \
  struct touchcloud::DataTypeName<CXX_TYPE> {                 \
    static constexpr std::string_view value = NAME;           \
  }

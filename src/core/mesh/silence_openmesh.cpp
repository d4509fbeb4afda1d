#include "silence_openmesh.h"

#include <OpenMesh/Core/System/omstream.hh>
#include <iostream>

namespace primo {

void silence_openmesh() {
  static const bool silenced = [] {
    for (OpenMesh::mostream* stream : {&omlog(), &omout(), &omerr()}) {
      stream->disable();
      stream->disconnect(std::clog);
      stream->disconnect(std::cout);
      stream->disconnect(std::cerr);
    }
    return true;
  }();
  (void)silenced;
}

}  // namespace primo

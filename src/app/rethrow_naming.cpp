#include "rethrow_naming.h"

#include <new>

#include "primo/util/error.h"

namespace primo::app {

// A message from the engine names what is wrong but not the file it came from.
void rethrow_naming(const std::string& file) {
  try {
    throw;
  } catch (const Error& e) {
    const std::string what = e.what();
    if (what.rfind(file + ":", 0) == 0) throw;
    throw Error(file + ": " + what);
  } catch (const std::bad_alloc&) {
    throw Error(file + ": out of memory (the mesh or the solver needs more than this machine has)");
  }
}

}  // namespace primo::app

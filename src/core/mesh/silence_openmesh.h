#pragma once
// Internal to the core library.

namespace primo {

// OpenMesh logs warnings and errors to the console; the library prints nothing. Disabling its
// streams is not enough: the OM writer re-enables omlog() (and then prints "#bytes written"),
// so the streams are also cut off from the console. Idempotent; affects the whole process.
void silence_openmesh();

}  // namespace primo

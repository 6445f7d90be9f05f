// tinyobjloader's implementation compiled into the fuzz harnesses, with the
// fuzzer's coverage and the sanitizers, in place of Debian's uninstrumented
// shared library: the OBJ and MTL harnesses then see inside the parser they
// mostly drive. The header is the library's own source, of the same package.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>

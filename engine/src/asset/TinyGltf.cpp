// The glTF parser: the tinygltf of Debian's libtinygltf-dev, its implementation compiled here so
// that the engine calls this copy and no other. libdraco exports a tinygltf of its own (built
// with its own Draco decoding); had the engine linked libtinygltf, which of the two
// its calls reached would depend on the order the libraries were loaded in (a program that links
// libdraco itself got draco's). The engine's library binds its own functions to itself
// (-Bsymbolic-functions, engine/CMakeLists.txt). The asset module builds it without stb: images
// are decoded by the loader's callback and never written.
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>

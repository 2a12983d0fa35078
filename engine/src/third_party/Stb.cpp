// stb_image and stb_image_write, from Debian's libstb-dev headers, compiled into the engine
// rather than linked from libstb: libdraco exports an stb_image of its own, and the engine's
// calls to a symbol it does not define reach whichever library the process loaded first, so with
// libstb they went to draco's copy. Defined here, they bind inside the engine's library
// (-Bsymbolic-functions). PNG and Radiance decoding only (asset/ImageChecks.h says which formats
// may reach stb: JPEG goes to libjpeg-turbo), PNG and Radiance writing.
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image.h>
#include <stb_image_write.h>

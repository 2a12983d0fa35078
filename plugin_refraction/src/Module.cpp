// Entry points of the loadable module (glass-capture --plugin PATH).
#include "refraction/RefractionPlugin.h"

GLASS_PLUGIN_ENTRY(refraction::RefractionPlugin)

// A deliberately wrong include: another folder's private header.
#include "../core/avx_internal.h"

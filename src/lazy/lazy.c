/* dlopen and dlsym for the stubs of lazy.h. */
#include "lazy/lazy.h"

#include <dlfcn.h>
#include <stdio.h>
#include <string.h>

int gm_lazy_open(gm_lazy_lib *lib) {
  if (lib->handle != NULL) return 1;
  lib->handle = dlopen(lib->soname, RTLD_NOW | RTLD_LOCAL);
  if (lib->handle == NULL) {
    fprintf(stderr, "geomint: cannot load %s: %s\n", lib->soname, dlerror());
    return 0;
  }
  return 1;
}

int gm_lazy_find(gm_lazy_lib *lib, const char *name, void *fn, size_t size) {
  void *sym = dlsym(lib->handle, name);
  if (sym == NULL || size != sizeof sym) {
    fprintf(stderr, "geomint: %s has no function %s\n", lib->soname, name);
    return 0;
  }
  memcpy(fn, &sym, size); /* object to function pointer, as POSIX dlsym intends */
  return 1;
}

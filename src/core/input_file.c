/* Opening a file the user named as input (a scene, a checkpoint): say what it is when it is
 * not a regular file, and never block. A directory opens fine with fopen on Linux and then
 * reads as an empty or truncated file; a FIFO without a writer blocks open(2) forever. The
 * file is opened with O_NONBLOCK (which makes open of a FIFO return at once), its type is
 * checked with fstat, and the flag is cleared again so that a pipe with a writer is read
 * normally (a FIFO without a writer then reads as end of file). */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/internal.h"

FILE *gm_input_open(const char *path, char *why, size_t cap) {
  int fd = open(path, O_RDONLY | O_NONBLOCK);
  if (fd < 0) {
    snprintf(why, cap, "cannot open %s: %s", path, strerror(errno));
    return NULL;
  }
  struct stat st;
  const char *kind = NULL;
  if (fstat(fd, &st) != 0)
    kind = "a file whose type cannot be read";
  else if (S_ISDIR(st.st_mode))
    kind = "a directory";
  else if (S_ISBLK(st.st_mode))
    kind = "a block device";
  else if (S_ISSOCK(st.st_mode))
    kind = "a socket";
  if (kind != NULL) {
    snprintf(why, cap, "%s is %s, not a file", path, kind);
    close(fd);
    return NULL;
  }
  int flags = fcntl(fd, F_GETFL);
  if (flags >= 0) (void)fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
  FILE *f = fdopen(fd, "rb");
  if (f == NULL) {
    snprintf(why, cap, "cannot open %s: %s", path, strerror(errno));
    close(fd);
  }
  return f;
}

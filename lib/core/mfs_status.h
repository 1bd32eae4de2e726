/* Status codes of libmfstab.  The library never prints or exits: every
 * function that can fail returns one of these, and mfs_strerror() names it. */
#ifndef MFS_STATUS_H
#define MFS_STATUS_H
#ifdef __cplusplus
extern "C" {
#endif

/* X(name, value, message): the one list every status comes from. */
#define MFS_STATUS_LIST(X)                                                        \
  X(MFS_OK, 0, "success")                                                         \
  X(MFS_ENOMEM, 1, "out of memory")                                               \
  X(MFS_EINVAL, 2, "invalid argument")                                            \
  X(MFS_ESINGULAR, 3, "singular or badly conditioned moment matrix")              \
  X(MFS_ENOTSUP, 4, "combination not supported")                                  \
  X(MFS_ETOOSMALL, 5, "model too small for the support radius")                   \
  X(MFS_ENOCONV, 6, "iteration did not converge")                                 \
  X(MFS_ELAPACK, 7, "LAPACK routine failed")                                      \
  X(MFS_EARPACK, 8, "ARPACK routine failed")                                      \
  X(MFS_EIO, 9, "input/output error")                                             \
  X(MFS_EDOMAIN, 10, "numerical failure (non-finite value)")                     \
  X(MFS_ESYSTEM, 11, "singular or badly conditioned linear system")

typedef enum {
#define MFS_X_ENUM(name, value, msg) name = value,
  MFS_STATUS_LIST(MFS_X_ENUM)
#undef MFS_X_ENUM
} mfs_status;

/* A static, human-readable description of a status code. */
const char *mfs_strerror(int status);

#ifdef __cplusplus
}
#endif

#endif

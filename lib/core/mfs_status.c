#include "mfs_status.h"

const char *mfs_strerror(int status)
{
  switch (status) {
#define MFS_X_CASE(name, value, msg) \
  case name:                         \
    return msg;
    MFS_STATUS_LIST(MFS_X_CASE)
#undef MFS_X_CASE
  default:
    return "unknown status";
  }
}

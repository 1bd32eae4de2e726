// A C++ client of the installed library: the headers compile as C++ (their
// extern "C" guards) and the C symbols link.  Checks the default
// descriptor, the kernel table and the critical step of lambda = 4:
// dt = 2 / sqrt(4) = 1.  Exits 1 on a wrong answer.
#include <cmath>
#include <cstdio>

#include <mfstab.h>

int main()
{
  mfs_disc d = mfs_disc_default();
  const char *field = nullptr;
  if (mfs_disc_check(&d, &field) != MFS_OK) {
    std::fprintf(stderr, "hello: the default descriptor is refused at %s\n", field);
    return 1;
  }
  double dt = mfs_dt_crit(4.0);
  std::printf("kernel %s, dilation %g, dt_crit(4) = %g, %s\n", d.kernel->name, d.dilation, dt,
              mfs_strerror(MFS_OK));
  return std::fabs(dt - 1.0) < 1e-15 ? 0 : 1;
}

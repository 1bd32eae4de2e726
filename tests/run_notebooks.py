#!/usr/bin/python3
"""Execute every notebook of notebooks/ with Debian's nbclient and ipykernel (the meson test of
suite 'notebooks'); exit 77 (meson: skipped) with a message when they are missing.

usage: /usr/bin/python3 tests/run_notebooks.py ROOT MFSTAB [--write DIR] [NOTEBOOK ...]
  ROOT     the source tree (notebooks/ and notebooks-data/ are read from it)
  MFSTAB   the built binary
  --write DIR   also save the executed notebooks (with their outputs) into DIR
Nothing is written into the source tree: the kernel runs in a temporary directory, the executed
notebooks are kept in memory (or written to DIR), Python writes no bytecode."""
import glob
import os
import re
import sys
import tempfile
import time

SKIP = 77
# importing ipykernel imports debugpy, which warns about frozen modules unless told not to
os.environ["PYDEVD_DISABLE_FILE_VALIDATION"] = "1"


def main(argv):
    args = argv[1:]
    write = None
    if "--write" in args:
        i = args.index("--write")
        write = args[i + 1]
        del args[i:i + 2]
    if len(args) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    root, mfstab, names = os.path.abspath(args[0]), os.path.abspath(args[1]), args[2:]
    try:
        import nbformat
        from nbclient import NotebookClient
        import ipykernel  # noqa: F401  (the kernel nbclient starts)
        import IPython  # noqa: F401
    except ImportError as e:
        print(f"SKIP: {e.name} is missing; the notebooks need Debian's python3-nbclient, python3-ipykernel "
              "and python3-nbformat (bash scripts/install-deps.sh installs them)", file=sys.stderr)
        return SKIP
    from jupyter_client.kernelspec import KernelSpecManager, NoSuchKernel
    try:
        KernelSpecManager().get_kernel_spec("python3")
    except NoSuchKernel:
        print("SKIP: no Jupyter kernel 'python3' (python3-ipykernel installs it)", file=sys.stderr)
        return SKIP
    if not os.path.exists(mfstab):
        print(f"FAIL: {mfstab}: mfstab is not built", file=sys.stderr)
        return 1
    paths = [os.path.join(root, "notebooks", n) for n in names] or \
        sorted(glob.glob(os.path.join(root, "notebooks", "*.ipynb")))
    if not paths:
        print(f"FAIL: no notebook in {root}/notebooks", file=sys.stderr)
        return 1
    os.environ.update({"MFSTAB_ROOT": root, "MFSTAB_DATA": os.path.join(root, "notebooks-data"),
                       "MFSTAB": mfstab, "PYTHONDONTWRITEBYTECODE": "1", "MPLBACKEND": "Agg"})
    failed = 0
    with tempfile.TemporaryDirectory(prefix="mfstab-notebooks-") as work:
        # the kernel's own files (IPython profile, matplotlib cache) go to the temporary directory too
        os.environ.update({"IPYTHONDIR": os.path.join(work, "ipython"), "MPLCONFIGDIR": os.path.join(work, "mpl"),
                           "JUPYTER_RUNTIME_DIR": os.path.join(work, "runtime")})
        for path in paths:
            name = os.path.basename(path)
            nb = nbformat.read(path, as_version=4)
            client = NotebookClient(nb, timeout=120, kernel_name="python3", resources={"metadata": {"path": work}})
            t0 = time.time()
            try:
                client.execute()
                status = "ok"
            except Exception as e:  # nbclient's CellExecutionError carries the cell and the traceback
                status = "FAILED"
                failed += 1
                msg = re.sub(r"\x1b\[[0-9;]*m", "", str(e))  # the traceback without terminal colours
                print(f"--- {name}:\n{msg}", file=sys.stderr)
            print(f"{name}: {status} ({len(nb.cells)} cells, {time.time() - t0:.1f} s)")
            if write:
                os.makedirs(write, exist_ok=True)
                nbformat.write(nb, os.path.join(write, name))
        left = [f for f in os.listdir(work) if f not in ("ipython", "mpl", "runtime")]
        if left:
            print(f"note: the notebooks wrote {left} into their working directory (a temporary one)")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

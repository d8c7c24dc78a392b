#!/usr/bin/env python3
"""cuda_kernels_built: the strahl binary holds the CUDA back end's kernels as sm_90 machine code and
compute_90 PTX (STRAHL_CUDA_ARCHITECTURES' default), registered under their names.

  kernels_built.py <strahl> [cuobjdump]

Reads the fatbinary section (.nv_fatbin) itself — nvcc's fatbinary container: a 16-byte header
(magic 0xBA55ED50), then entries whose headers give the kind (1 PTX, 2 ELF), the sizes and the
architecture — so it needs no cuobjdump (which not every CUDA installation has); with one given,
its --list-elf / --list-ptx must agree."""
import shutil
import struct
import subprocess
import sys
import tempfile


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def fatbin_entries(blob):
    entries, pos = [], 0
    while pos + 16 <= len(blob):
        magic, _version, header_size, fat_size = struct.unpack_from("<IHHQ", blob, pos)
        if magic != 0xBA55ED50:
            break
        p, end = pos + header_size, pos + header_size + fat_size
        while p + 32 <= end:
            kind, _u, eh_size, size, _csize, _u2, minor, major, arch = struct.unpack_from("<HHIQIIHHI", blob, p)
            entries.append(("ptx" if kind == 1 else "elf" if kind == 2 else str(kind), arch))
            p += eh_size + size
        pos = end
        while pos < len(blob) and pos % 8:  # containers are 8-byte aligned
            pos += 1
    return entries


def main():
    strahl = sys.argv[1]
    with tempfile.NamedTemporaryFile() as tmp:
        r = subprocess.run(["objcopy", "-O", "binary", "--only-section=.nv_fatbin", strahl, tmp.name],
                           capture_output=True, text=True)
        if r.returncode != 0:
            fail("objcopy: " + r.stderr)
        blob = open(tmp.name, "rb").read()
    if not blob:
        fail("no .nv_fatbin section in " + strahl)
    entries = fatbin_entries(blob)
    print("fatbinary entries:", entries)
    if ("elf", 90) not in entries:
        fail("no sm_90 machine code")
    if ("ptx", 90) not in entries:
        fail("no compute_90 PTX")
    image = open(strahl, "rb").read()
    for kernel in (b"render_kernel", b"primary_kernel"):
        if kernel not in image:
            fail("no kernel named %s registered" % kernel.decode())
    cuobjdump = sys.argv[2] if len(sys.argv) > 2 else shutil.which("cuobjdump")
    if cuobjdump:
        elf = subprocess.run([cuobjdump, "--list-elf", strahl], capture_output=True, text=True).stdout
        ptx = subprocess.run([cuobjdump, "--list-ptx", strahl], capture_output=True, text=True).stdout
        print(elf + ptx)
        if "sm_90" not in elf or "sm_90" not in ptx:
            fail("cuobjdump disagrees")
    print("all checks passed")


if __name__ == "__main__":
    main()

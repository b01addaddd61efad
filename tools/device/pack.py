#!/usr/bin/env python3
"""Packs build/app/deepgi and the shared libraries it loads into one archive for a GPU machine whose
image is not Debian 12 and has no package registry (the device tool's nvidia-h200).

OpenImageIO (and OSMesa) pull in ~565 MB of libraries (ffmpeg, OpenCV, GDAL, OpenVDB, LLVM) that
deepgi never calls when it writes EXR/PNG through EGL; those are replaced by stubs with the same
SONAME, version nodes and symbols (BIND_NOW libraries need every import to resolve), each of which
prints its name and aborts if it is ever called. glibc and libstdc++ stay the machine's own.

usage: tools/device/pack.py OUT.tar.xz
"""
import os, re, subprocess, sys, tempfile, tarfile

STUB = {  # loaded by OpenImageIO/OSMesa, never called for EXR/PNG output through EGL
    "libopencv_core.so.406", "libopencv_imgproc.so.406", "libopencv_videoio.so.406",
    "libdcmimage.so.17", "libdcmimgle.so.17", "libdcmdata.so.17", "liboflog.so.17", "libofstd.so.17",
    "libavcodec.so.59", "libavformat.so.59", "libavutil.so.57", "libswscale.so.6",
    "libgif.so.7", "libheif.so.1", "libopenjp2.so.7", "libopenvdb.so.10.0", "libraw_r.so.20",
    "libwebp.so.7", "libwebpdemux.so.2", "libOSMesa.so.8", "libglfw.so.3",
}
SYSTEM = {  # the machine's own (glibc, the C++ runtime) or the glvnd debs the device README names
    "libc.so.6", "libm.so.6", "libdl.so.2", "libpthread.so.0", "librt.so.1", "ld-linux-x86-64.so.2",
    "libstdc++.so.6", "libgcc_s.so.1", "libEGL.so.1", "libGL.so.1", "libGLX.so.0", "libOpenGL.so.0",
    "libGLdispatch.so.0",
}
LIBDIRS = ["/lib/x86_64-linux-gnu", "/usr/lib/x86_64-linux-gnu"]


def find(soname):
    for d in LIBDIRS:
        p = os.path.join(d, soname)
        if os.path.exists(p):
            return p
    raise SystemExit(f"pack: {soname} not found in {LIBDIRS}")


def needed(path):
    out = subprocess.run(["readelf", "-d", path], capture_output=True, text=True, check=True).stdout
    return re.findall(r"\(NEEDED\)\s+Shared library: \[(.+?)\]", out)


def stub(real, soname, outdir):
    """Writes outdir/soname: same SONAME, version nodes and exported symbols as `real`."""
    out = subprocess.run(["readelf", "--dyn-syms", "-W", real], capture_output=True, text=True, check=True).stdout
    syms, versions = [], []
    for line in out.splitlines():
        f = line.split()
        if len(f) < 8 or not f[0].endswith(":") or f[6] == "UND" or f[4] not in ("GLOBAL", "WEAK"):
            continue
        if f[4] == "WEAK":  # C++ template and inline copies: a stub's copy would interpose the working one
            continue
        kind, size, name = f[3], int(f[2], 0), f[7]
        base, sep, ver = re.match(r"([^@]+)(@@|@)?(.*)", name).groups()
        if f[6] == "ABS":  # a version node's own symbol: the version script makes it
            versions.append(base) if base not in versions else None
            continue
        if ver and ver not in versions:
            versions.append(ver)
        syms.append((kind, max(size, 8), base, sep or "", ver))
    die = "__stub_die"
    asm = [".section .note.GNU-stack,\"\",@progbits", ".section .rodata", f"__stub_lib: .asciz \"{soname}\"",
           "__stub_version: .asciz \"0 (stub)\"", ".text", f"{die}:", "  lea __stub_lib(%rip), %rdi", "  jmp deepgi_device_stub_called@PLT"]
    for i, (kind, size, base, sep, ver) in enumerate(syms):
        local = f"__stub_{i}"
        asm.append(f".globl {local}")  # a .symver alias takes its source's binding; the version script hides the source
        if kind in ("FUNC", "IFUNC", "NOTYPE") and re.search(r"[CD][012]Ev$", base):
            # default constructors and destructors of static registration objects (dcmtk's DiRegister) run at load
            asm += [".text", f".type {local}, @function", f"{local}: ret"]
        elif kind in ("FUNC", "IFUNC", "NOTYPE") and re.search(r"version", base, re.I) and not base.startswith("_Z"):
            # OpenImageIO's plugin catalogue asks every format library its version (opj_version, av_version_info)
            asm += [".text", f".type {local}, @function", f"{local}: lea __stub_version(%rip), %rax", "  ret"]
        elif kind in ("FUNC", "IFUNC", "NOTYPE"):
            asm += [".section .rodata", f"__name_{i}: .asciz \"{base}\"", ".text", f".type {local}, @function",
                    f"{local}: lea __name_{i}(%rip), %rsi", f"  jmp {die}"]
        elif kind == "TLS":
            asm += [".section .tbss,\"awT\",@nobits", f".type {local}, @object", f".size {local}, {size}",
                    f"{local}: .zero {size}"]
        else:
            asm += [".bss", ".balign 16", f".type {local}, @object", f".size {local}, {size}", f"{local}: .zero {size}"]
        if sep:
            asm.append(f".symver {local}, {base}{sep}{ver}")
        else:
            asm += [f".globl {base}", f".set {base}, {local}"]
    script = "".join(f"{v} {{ {'local: __stub_*;' if k == 0 else ''} }};\n" for k, v in enumerate(versions)) \
        or "{ local: __stub_*; };\n"
    with tempfile.TemporaryDirectory() as t:
        open(f"{t}/s.S", "w").write("\n".join(asm) + "\n")
        open(f"{t}/v.map", "w").write(script)
        open(f"{t}/die.c", "w").write(
            '#include <stdio.h>\n#include <stdlib.h>\n__attribute__((visibility("hidden"))) void '
            'deepgi_device_stub_called(const char* lib, const char* sym) { fprintf(stderr, "deepgi device pack: '
            '%s in %s was called, but that library is a stub\\n", sym, lib); abort(); }\n')
        subprocess.run(["gcc", "-shared", "-fPIC", "-o", os.path.join(outdir, soname), f"-Wl,-soname,{soname}",
                        f"-Wl,--version-script={t}/v.map", f"{t}/s.S", f"{t}/die.c"], check=True)


def main():
    if len(sys.argv) != 2:
        raise SystemExit(__doc__)
    exe = "build/app/deepgi"
    keep, stubs, todo = {}, set(), list(needed(exe))
    while todo:
        so = todo.pop()
        if so in SYSTEM or so in keep or so in stubs:
            continue
        if so in STUB:
            stubs.add(so)
            continue
        keep[so] = find(so)
        todo += needed(keep[so])
    with tempfile.TemporaryDirectory() as t:
        os.makedirs(f"{t}/lib")
        for so in sorted(stubs):
            stub(find(so), so, f"{t}/lib")
        subprocess.run(["strip", "-o", f"{t}/deepgi", exe], check=True)
        with tarfile.open(sys.argv[1], "w:xz") as tar:
            tar.add(f"{t}/deepgi", "deepgi")
            for so, p in sorted(keep.items()):
                tar.add(os.path.realpath(p), f"lib/{so}")
            for so in sorted(stubs):
                tar.add(f"{t}/lib/{so}", f"lib/{so}")
    print(f"pack: {len(keep)} libraries, {len(stubs)} stubs -> {sys.argv[1]} "
          f"({os.path.getsize(sys.argv[1]) / 1e6:.1f} MB)")


if __name__ == "__main__":
    main()

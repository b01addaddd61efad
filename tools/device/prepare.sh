#!/usr/bin/env bash
# Prepares the ignored folders that tools/device/gpu_figures.sh reads on a lent GPU machine (see its header), from
# the repository root after a build: .dev (the packed binary, the scenes, an llvmpipe frame to compare with, the hard
# suite's reference cache, a font) and .gl (the glvnd debs the device README names). Then, with the device tool:
#   run  command="bash tools/device/gpu_figures.sh"  carry=[".dev", ".gl"]  (about 5 minutes for all steps)
# HARD_CACHE: a hard-suite reference cache to reuse (default /tmp/bh/cache; built here when missing, ~7 min).
set -euo pipefail
cd "$(dirname "$0")/../.."
grep -qx '/.dev/' .git/info/exclude 2>/dev/null || { mkdir -p .git/info; echo /.dev/ >> .git/info/exclude; }
mkdir -p .dev/fonts .gl
python3 tools/device/pack.py .dev/deepgi.tar.xz

# The scenes beside the checkout, under the 64 MiB a call carries: Sponza's 3-channel textures as JPEG (quality 92,
# the same sizes, so the same sampling cost), the MTL pointed at them; the Cornell boxes as they are.
shared=../shared/scenes
tmp=$(mktemp -d)
mkdir -p "$tmp/CrytekSponza/textures"
cp "$shared/CrytekSponza/"{sponza.obj,sponza.mtl,README.md,copyright.txt} "$tmp/CrytekSponza/"
chmod u+w "$tmp/CrytekSponza/"*
for f in "$shared/CrytekSponza/textures/"*.png; do
    b=$(basename "$f" .png)
    if oiiotool --info "$f" | grep -q "3 channel"; then
        oiiotool "$f" --compression jpeg:92 -o "$tmp/CrytekSponza/textures/$b.jpg"
        sed -i "s#textures\\\\$b.png#textures\\\\$b.jpg#" "$tmp/CrytekSponza/sponza.mtl"
    else
        cp "$f" "$tmp/CrytekSponza/textures/"
    fi
done
cp -r "$shared/CornellBox" "$tmp/"
tar cJf .dev/scenes.tar.xz -C "$tmp" .
rm -rf "$tmp"

# The frame the GPU must reproduce: the software-GL defaults, made here on llvmpipe.
build/app/deepgi render --size 640x360 --frames 24 --set radiosity.resolution=quarter --set radiosity.interleave=4 \
    --out /tmp/deepgi_llvmpipe_640 > /dev/null
cp /tmp/deepgi_llvmpipe_640/final.exr .dev/atrium_640_llvmpipe.exr

cache=${HARD_CACHE:-/tmp/bh/cache}
if [ ! -d "$cache" ]; then
    build/app/deepgi bench --suite hard --scales 1 --no-path --cache "$cache" --out /tmp/deepgi_hard_refs \
        --hard-scenes offscreen_light,thin_wall,hidden_emitter,sun_patch,furnace --whole-frame-size 0x0 --quiet
fi
rm -rf .dev/hard_cache && cp -r "$cache" .dev/hard_cache
cp /usr/share/fonts/truetype/dejavu/DejaVuSans.ttf .dev/fonts/

o='-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists=/tmp/amd64'
mkdir -p /tmp/amd64/partial
apt-get $o update > /dev/null
(cd .gl && apt-get $o download libvulkan1 libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2)
du -sh .dev .gl

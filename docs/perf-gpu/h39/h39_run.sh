C=build-h27; for f in "$C"/gl/*.deb; do dpkg -x "$f" /; done; ldconfig
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json LD_LIBRARY_PATH=$PWD/$C/lib
G=$C/gblens; M=$1
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > $OUT/device.txt
s=$(date +%s)
$G bench --only methods --methods-sizes 1920x1080,3840x2160 --methods-lights 256,65536 --methods-forward-max 0 \
  --methods-rounds 3 --methods-min-rounds 2 --methods-seconds 40 --methods-culling-max 0 --gbuffer $M --out /tmp/b_$M > $OUT/h39_$M.log 2>&1
echo "rc $? in $(( $(date +%s) - s )) s" >> $OUT/h39_$M.log
cp /tmp/b_$M/bench.json $OUT/h39_$M.json; cp /tmp/b_$M/bench.md $OUT/h39_$M.md
tail -3 $OUT/h39_$M.log

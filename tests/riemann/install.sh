#!/usr/bin/env bash
# Install the built tree into a temporary prefix, then build and run an outside program against it
# with find_package(sabre) (shared and static) and with pkg-config. Usage: install.sh BUILD_DIR SRC_DIR
set -eu
build=$1; src=$2
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" > /dev/null
cmake -S "$src/install" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$work/prefix" > /dev/null
cmake --build "$work/consumer" > /dev/null
LD_LIBRARY_PATH="$work/prefix/lib:$work/prefix/lib/x86_64-linux-gnu" "$work/consumer/consumer_cmake"
"$work/consumer/consumer_cmake_static"
pcdir=$(dirname "$(find "$work/prefix" -name sabre-riemann.pc)")
flags=$(PKG_CONFIG_PATH="$pcdir" pkg-config --cflags --libs sabre-riemann)
libdir=$(PKG_CONFIG_PATH="$pcdir" pkg-config --variable=libdir sabre-riemann)
cc -std=c17 "$src/install/main.c" $flags -lm -o "$work/consumer_pc"
LD_LIBRARY_PATH="$libdir" "$work/consumer_pc"
"$work/prefix/bin/sabre-riemann" boundary --xi 7 --rho0 1000 --c0 20 --interior 1000,0 --pressure 10 > /dev/null
echo "install: 4 passed, 0 failed"

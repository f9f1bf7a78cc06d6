#!/usr/bin/env bash
# Start a new scene from the skeleton: copies its folders
#   include/granular_dg/equations/skeleton  source/equations/skeleton  tests/skeleton
# to .../NAME and renames skeleton -> NAME inside them. The scene registers
# itself and CMake finds its files: no file outside the new folders changes.
#
#   bash contrib/new_scene.sh NAME        (NAME: lower case, digits, '_')
#   cmake --build build && build/granular_dg --list-scenes
set -euo pipefail
cd "$(dirname "$0")/.."
name=${1:-}
if [[ ! "$name" =~ ^[a-z][a-z0-9_]*$ ]]; then
  echo "usage: $0 NAME   (NAME: a lower-case identifier, e.g. shallow_water)" >&2
  exit 2
fi
Name="$(tr '[:lower:]' '[:upper:]' <<< "${name:0:1}")${name:1}"
for dir in include/granular_dg/equations source/equations tests; do
  if [ -e "$dir/$name" ]; then
    echo "$0: $dir/$name exists already" >&2
    exit 2
  fi
done
for dir in include/granular_dg/equations source/equations tests; do
  cp -r "$dir/skeleton" "$dir/$name"
  find "$dir/$name" -type f -exec sed -i -e "s/skeleton/$name/g" -e "s/Skeleton/$Name/g" {} +
done
echo "new scene '$name': include/granular_dg/equations/$name, source/equations/$name, tests/$name"
echo "next: edit system.h (the physics), parameters.* and scene.cc; build; granular_dg --list-scenes"

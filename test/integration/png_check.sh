# Sourced by the plotting tests: png DIR NAME... checks that each DIR/NAME.png exists, is
# non-empty and starts with the PNG signature (else it prints which and exits 1).
png() {
  folder=$1
  shift
  for name in "$@"; do
    file="$folder/$name.png"
    if [ ! -s "$file" ] || [ "$(head -c 4 "$file" | tail -c 3)" != "PNG" ]; then
      echo "missing, empty or not a PNG: $file"
      exit 1
    fi
    echo "$name.png: $(wc -c < "$file") bytes"
  done
}

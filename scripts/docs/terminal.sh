# Sourced by the figure scripts: out=docs/img, and a PNG terminal of the given size (gnuplot-nox may lack
# cairo; then the libgd png terminal).
out="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)/docs/img"
mkdir -p "$out"
png_terminal() {
  if gnuplot -e 'set terminal' 2>&1 | grep -q pngcairo; then
    echo "pngcairo size $1,$2 font ',9'"
  else
    echo "png size $1,$2"
  fi
}

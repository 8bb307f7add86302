/* png2ppm.c: the picture tests' PNG reader. Reads a PNG with cairo and
** writes it to stdout as a binary PPM (P6, 8-bit RGB; alpha composited on
** white). Usage: png2ppm FILE.png */
#include <cairo.h>
#include <stdint.h>
#include <stdio.h>

int main(int argc, char **argv) {
  if (argc != 2) {
    fprintf(stderr, "usage: png2ppm FILE.png\n");
    return 2;
  }
  cairo_surface_t *s = cairo_image_surface_create_from_png(argv[1]);
  if (cairo_surface_status(s)) {
    fprintf(stderr, "png2ppm: %s: %s\n", argv[1],
            cairo_status_to_string(cairo_surface_status(s)));
    return 1;
  }
  int w = cairo_image_surface_get_width(s), h = cairo_image_surface_get_height(s);
  int stride = cairo_image_surface_get_stride(s);
  int alpha = cairo_image_surface_get_format(s) == CAIRO_FORMAT_ARGB32;
  const unsigned char *d = cairo_image_surface_get_data(s);
  printf("P6\n%d %d\n255\n", w, h);
  for (int y = 0; y < h; y++)
    for (int x = 0; x < w; x++) {
      uint32_t p = *(const uint32_t *)(d + (size_t)y * stride + 4 * (size_t)x);
      unsigned a = alpha ? p >> 24 : 255;
      unsigned char rgb[3] = {(p >> 16) & 255, (p >> 8) & 255, p & 255};
      for (int k = 0; k < 3; k++) rgb[k] = (unsigned char)(rgb[k] + (255 - a));
      fwrite(rgb, 1, 3, stdout);
    }
  cairo_surface_destroy(s);
  return 0;
}

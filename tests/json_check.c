/* json_check FILE FIELD...: exit 0 if FILE holds exactly one JSON object that has every FIELD
 * (a field "a.b" looks inside object a; "a[0].b" inside the first element of array a).
 * Used by the CTest entries that run the dem-* programs (tests/CMakeLists.txt). */
#include <jansson.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static json_t *lookup(json_t *root, const char *path) {
  char buf[256];
  snprintf(buf, sizeof buf, "%s", path);
  json_t *cur = root;
  for (char *tok = strtok(buf, "."); tok && cur; tok = strtok(NULL, ".")) {
    char *br = strchr(tok, '[');
    if (br) {
      *br = '\0';
      cur = json_object_get(cur, tok);
      cur = json_array_get(cur, (size_t)atoi(br + 1));
    } else {
      cur = json_object_get(cur, tok);
    }
  }
  return cur;
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: json_check FILE FIELD...\n");
    return 2;
  }
  json_error_t e;
  json_t *root = json_load_file(argv[1], 0, &e);
  if (!root) {
    fprintf(stderr, "json_check: %s:%d: %s\n", argv[1], e.line, e.text);
    return 1;
  }
  if (!json_is_object(root)) {
    fprintf(stderr, "json_check: %s: not one JSON object\n", argv[1]);
    return 1;
  }
  int bad = 0;
  for (int i = 2; i < argc; i++)
    if (!lookup(root, argv[i])) {
      fprintf(stderr, "json_check: %s: field '%s' missing\n", argv[1], argv[i]);
      bad = 1;
    }
  json_decref(root);
  return bad;
}

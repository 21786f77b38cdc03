// Bundles the app (web/src/main.js: CodeMirror 6 and the engine's client)
// with esbuild and writes ONE self-contained page: the template
// web/src/index.html with the bundle inlined; the engine's wasm (base64)
// and wasm-bindgen's glue (text) are imported by the bundle, so nothing is
// fetched at run time. Called by tools/build-web.sh:
//   node web/build.mjs PKG_DIR OUT.html
import { build } from "esbuild";
import { readFileSync, writeFileSync, mkdirSync } from "node:fs";
import { dirname, join, resolve } from "node:path";
import { fileURLToPath } from "node:url";

const here = dirname(fileURLToPath(import.meta.url));
const [pkg, outFile] = process.argv.slice(2);
if (!pkg || !outFile) {
  console.error("usage: node web/build.mjs PKG_DIR OUT.html");
  process.exit(2);
}
// The generated engine, reached from the app as "vcnc-engine".
const engine = {
  name: "vcnc-engine",
  setup(b) {
    b.onResolve({ filter: /^vcnc-engine$/ }, () => ({ path: "vcnc-engine", namespace: "vcnc" }));
    b.onLoad({ filter: /.*/, namespace: "vcnc" }, () => ({
      contents:
        "export const WASM = " + JSON.stringify(readFileSync(join(resolve(pkg), "vcnc_web_bg.wasm")).toString("base64")) + ";\n" +
        "export const GLUE = " + JSON.stringify(readFileSync(join(resolve(pkg), "vcnc_web.js"), "utf8")) + ";\n",
      loader: "js",
    }));
  },
};
const result = await build({
  entryPoints: [join(here, "src/main.js")],
  bundle: true,
  minify: true,
  format: "iife",
  target: ["chrome103", "firefox113", "safari16.4"],
  write: false,
  loader: { ".wjs": "text" },
  plugins: [engine],
  legalComments: "eof",
});
// Inline: no "</script" may close the element early.
const js = result.outputFiles[0].text.replace(/<\/(script)/gi, "<\\/$1");
const template = readFileSync(join(here, "src/index.html"), "utf8");
const [head, tail] = template.split("__APP__");
mkdirSync(dirname(outFile), { recursive: true });
writeFileSync(outFile, head + js + tail);
console.log("wrote " + outFile + " (" + Math.round((head.length + js.length + tail.length) / 1024) + " KiB)");

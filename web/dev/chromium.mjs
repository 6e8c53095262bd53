// How the tests start Debian's Chromium headless (tests/browser/, web/dev/check-page.mjs).
// There is no GPU here: WebGL runs on SwiftShader (software) through ANGLE, which these flags allow. No
// --disable-gpu: with it Chromium composites in software, reads the WebGL canvas back every frame and logs a
// "GPU stall due to ReadPixels" console warning for the page. The networking flags keep Chromium from calling
// home on a machine without network access.
export const CHROMIUM_ARGS = [
  '--headless=new',
  '--no-sandbox',
  '--enable-unsafe-swiftshader',
  '--use-angle=swiftshader',
  '--use-gl=angle',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
  '--no-first-run',
  '--disable-quic',
];

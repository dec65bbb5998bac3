// Builds the report template: ONE self-contained HTML file (dist/report.html) with every script
// and style inlined, so the C++ CLI can copy it, replace the data placeholder and hand the user a
// single file that opens from file:// with no network.
import { defineConfig } from 'vite';
import { viteSingleFile } from 'vite-plugin-singlefile';

export default defineConfig({
  // Relative URLs: nothing may point at a server root when opened from file://.
  base: './',
  plugins: [viteSingleFile({ removeViteModuleLoader: true })],
  build: {
    outDir: 'dist',
    emptyOutDir: true,
    // A source map could not be inlined usefully and a reference to one would make the browser
    // try to fetch it: none.
    sourcemap: false,
    target: 'es2022',
    rolldownOptions: { input: 'report.html' },
  },
});

// Unit tests run in node: the modules they cover (decoding, maths, fragment parsing) touch no DOM.
import { defineConfig } from 'vitest/config';

export default defineConfig({
  test: {
    include: ['tests/**/*.test.ts'],
    environment: 'node',
  },
});

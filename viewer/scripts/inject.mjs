// Puts a report's JSON into the built template exactly as the C++ CLI does: the one occurrence of
// the placeholder in dist/report.html is replaced by the JSON, with every "</" written "<\/" so no
// string in the data (a scene file's text, say) can close the <script> element that holds it.
//
// "<!--" is written "\u003c!--" as well: in a script element "<!--" followed later by "<script"
// changes how the HTML parser looks for the end of the element. Both are valid JSON escapes inside
// strings, the only place "<" can occur in JSON.

export const PLACEHOLDER = '__TUMBLE_DATA__';

export function escapeForScript(jsonText) {
  return jsonText.replaceAll('</', '<\\/').replaceAll('<!--', '\\u003c!--');
}

export function injectReport(templateHtml, jsonText) {
  const parts = templateHtml.split(PLACEHOLDER);
  if (parts.length !== 2) {
    throw new Error(`the template must contain the placeholder exactly once, found ${parts.length - 1}`);
  }
  // join, not String.replace: a replacement string's "$&" or "$1" would be expanded.
  return parts.join(escapeForScript(jsonText));
}

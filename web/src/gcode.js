// G-code colouring for CodeMirror 6: a stream tokenizer (one line at a
// time, no parse tree: programs run to millions of lines) whose comment
// and macro rules follow the dialect. It colours; it never judges — the
// engine's diagnostics do that.
import { StreamLanguage, HighlightStyle } from "@codemirror/language";
import { tags as t } from "@lezer/highlight";

// Dialects whose `;` starts a comment (the rest read it as end of block).
const SEMICOLON = new Set(["linuxcnc", "grbl", "haas", "syntec"]);
const MACRO_WORDS = /^(IF|THEN|GOTO|WHILE|DO|END|AND|OR|XOR|NOT|EQ|NE|GT|GE|LT|LE|MOD|SIN|COS|TAN|ASIN|ACOS|ATAN|SQRT|ABS|ROUND|FIX|FUP|LN|EXP|POW|BIN|BCD|ELSE|ENDIF|ENDWHILE|FOR|TO|BY|ENDFOR|REPEAT|UNTIL|CASE|OF|ENDCASE|SUB|ENDSUB|CALL|RETURN|EXISTS|SIGN)\b/i;

export function gcodeLanguage(dialect) {
  const semicolon = SEMICOLON.has(dialect);
  return StreamLanguage.define({
    name: "gcode",
    startState: () => ({ inComment: false }),
    token(stream, state) {
      if (state.inComment) {
        if (stream.skipTo(")")) { stream.next(); state.inComment = false; } else stream.skipToEnd();
        return "comment";
      }
      if (stream.eatSpace()) return null;
      const ch = stream.peek();
      if (ch === "(") { stream.next(); state.inComment = true; return "comment"; }
      if (ch === ";" && semicolon) { stream.skipToEnd(); return "comment"; }
      if (ch === "/" && stream.sol()) { stream.next(); return "meta"; }
      if (ch === "%") { stream.next(); return "meta"; }
      if (ch === "#") { stream.next(); stream.match(/^<[^>]*>|^\d+/); return "variableName.special"; }
      if (stream.match(MACRO_WORDS)) return "controlKeyword";
      if (stream.match(/^[Gg]\s*[-+]?\d+(\.\d+)?/)) return "keyword";
      if (stream.match(/^[Mm]\s*\d+/)) return "atom";
      if (stream.match(/^[Nn]\s*\d+/)) return "labelName";
      if (stream.match(/^[Oo]\s*\d+/) || stream.match(/^[Oo]<[^>]*>/)) return "labelName";
      if (stream.match(/^[TtHhDd]\s*\d+/)) return "typeName";
      if (stream.match(/^[FfSs]\s*[-+]?(\d+\.?\d*|\.\d+)/)) return "string";
      if (stream.match(/^[A-Za-z]\s*[-+]?(\d+\.?\d*|\.\d+)/)) return "propertyName";
      if (stream.match(/^[-+]?(\d+\.?\d*|\.\d+)/)) return "number";
      if (stream.match(/^[[\]]/)) return "bracket";
      stream.next();
      return null;
    },
    languageData: { commentTokens: { block: { open: "(", close: ")" } } },
  });
}

export const gcodeHighlight = HighlightStyle.define([
  { tag: t.comment, color: "#6a737d", fontStyle: "italic" },
  { tag: t.keyword, color: "#0b57d0", fontWeight: "bold" },
  { tag: t.atom, color: "#8a2be2", fontWeight: "bold" },
  { tag: t.labelName, color: "#8a8f98" },
  { tag: t.typeName, color: "#b35c00" },
  { tag: t.string, color: "#1a7f37" },
  { tag: t.propertyName, color: "#1c1e24" },
  { tag: t.number, color: "#005cc5" },
  { tag: t.special(t.variableName), color: "#c2185b" },
  { tag: t.controlKeyword, color: "#c2185b", fontWeight: "bold" },
  { tag: t.meta, color: "#d73a49" },
]);

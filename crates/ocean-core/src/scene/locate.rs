//! Where a key is in the scene text, so that every error names its line and column.

/// The dotted key written at `span` when the parse tree cannot say (a duplicate key fails the
/// parse, so it is not in any tree): the key before `=` on that line, under the nearest table
/// header above it.
pub(super) fn key_of_line(text: &str, span: std::ops::Range<usize>) -> Option<String> {
    let line_start = text[..span.start.min(text.len())].rfind('\n').map_or(0, |i| i + 1);
    let line = text[line_start..].lines().next()?;
    let key = line.split('=').next()?.trim().trim_matches('"');
    let valid = !key.is_empty() && !key.starts_with('[') && !key.starts_with('#');
    if !valid {
        return None;
    }
    let table = text[..line_start].lines().rev().map(str::trim).find_map(|l| {
        let inner = l.strip_prefix('[')?.split(']').next()?;
        Some(inner.trim_matches(['[', ']']).trim().to_owned())
    });
    Some(match table {
        Some(t) if !t.is_empty() => format!("{t}.{key}"),
        _ => key.to_owned(),
    })
}

pub(super) fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(text.len());
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    (line, text[line_start..offset].chars().count() + 1)
}

/// The dotted key path whose key or value covers a byte offset (the innermost one), so that
/// a serde error, which knows only a span, can name its key.
pub(super) fn key_at_offset(text: &str, offset: usize) -> Option<String> {
    use toml::de::{DeTable, DeValue};
    // A `[table]` header's span does not cover its body, so tables are always searched;
    // leaves match when their key or value covers the offset.
    fn walk(table: &DeTable<'_>, offset: usize, path: &mut Vec<String>) -> bool {
        for (k, v) in table.iter() {
            let here = k.span().contains(&offset) || v.span().contains(&offset);
            path.push(k.get_ref().to_string());
            let found = match v.get_ref() {
                DeValue::Table(t) => walk(t, offset, path) || here,
                DeValue::Array(a) => {
                    let mut inside = false;
                    for (i, elem) in a.iter().enumerate() {
                        path.push(i.to_string());
                        inside = match elem.get_ref() {
                            DeValue::Table(t) => walk(t, offset, path),
                            _ => false,
                        } || elem.span().contains(&offset);
                        if inside {
                            break;
                        }
                        path.pop();
                    }
                    inside || here
                }
                _ => here,
            };
            if found {
                return true;
            }
            path.pop();
        }
        false
    }
    let doc = DeTable::parse(text).ok()?;
    let mut path = Vec::new();
    walk(doc.get_ref(), offset, &mut path).then(|| path.join("."))
}

/// The position of a dotted key path (`ocean.resolution`, `objects.1.radius`) in the
/// document: the key itself, or the table header when the key is absent (a defaulted value
/// can still be inconsistent with others).
pub(super) fn key_position(text: &str, path: &str) -> Option<(usize, usize)> {
    use toml::de::{DeTable, DeValue};
    let doc = DeTable::parse(text).ok()?;
    let mut table: &DeTable<'_> = doc.get_ref();
    let mut best: Option<usize> = None;
    let parts: Vec<&str> = path.split('.').collect();
    let mut i = 0;
    while i < parts.len() {
        // An absent key (a defaulted or missing value) is reported at its table.
        let Some((k, v)) = table.iter().find(|(k, _)| k.get_ref().as_ref() == parts[i]) else {
            break;
        };
        best = Some(k.span().start);
        match v.get_ref() {
            DeValue::Table(t) => table = t,
            DeValue::Array(a) if i + 1 < parts.len() => {
                let idx: usize = parts[i + 1].parse().ok()?;
                let elem = a.get(idx)?;
                best = Some(elem.span().start);
                match elem.get_ref() {
                    DeValue::Table(t) => table = t,
                    _ => break,
                }
                i += 1;
            }
            _ => break,
        }
        i += 1;
    }
    best.map(|b| line_column(text, b))
}

//! A TrueType font cut down to the characters a document uses, for the SVG back end to embed
//! (issue 32 item 6: a slide made on another machine keeps its layout).
//!
//! The subset keeps glyph 0 (the missing-glyph box), the glyphs of the given characters and the
//! glyphs their composites are built from, renumbered in that order (composites' component
//! indices rewritten), and the tables a browser needs to draw them: `head` (long `loca`),
//! `hhea` and `hmtx` (one advance and left side bearing per kept glyph), `maxp` (the new
//! glyph count), `OS/2`, `name` (the font's names and licence, as they were), `post` (version 3,
//! no glyph names), `glyf`, `loca` and a `cmap` of one format-12 subtable (Windows, full
//! Unicode), one group per character. The layout tables (`GDEF`, `GPOS`, `GSUB`) are left out:
//! the canvas lays text out by advances alone (`text`'s module doc: no kerning), so a viewer
//! that kerned with them would place the glyphs where the PNG does not.
//!
//! Table checksums and `head.checkSumAdjustment` are computed as the OpenType specification
//! says: the sum of the big-endian u32 words of a table padded with zeros to 4 bytes, and
//! `0xB1B0AFBA` minus the sum over the whole font.

use std::collections::BTreeMap;

/// The magic number `head.checkSumAdjustment` is computed from (OpenType `head`).
const CHECKSUM_MAGIC: u32 = 0xB1B0_AFBA;
/// Composite glyph flags (OpenType `glyf`): the arguments are 16-bit words; one scale; two
/// scales; a 2×2 matrix; more components follow.
const ARG_1_AND_2_ARE_WORDS: u16 = 0x0001;
const WE_HAVE_A_SCALE: u16 = 0x0008;
const MORE_COMPONENTS: u16 = 0x0020;
const WE_HAVE_AN_X_AND_Y_SCALE: u16 = 0x0040;
const WE_HAVE_A_TWO_BY_TWO: u16 = 0x0080;
/// The most nested a composite may be before the subset gives up on its components (the
/// specification's fonts nest a few levels; a loop in a broken font must end).
const MAX_COMPOSITE_DEPTH: usize = 8;

/// A font file's tables, by tag.
struct Tables<'a> {
    tables: BTreeMap<[u8; 4], &'a [u8]>,
}

fn u16_at(b: &[u8], at: usize) -> Option<u16> {
    Some(u16::from_be_bytes(b.get(at..at + 2)?.try_into().ok()?))
}

fn u32_at(b: &[u8], at: usize) -> Option<u32> {
    Some(u32::from_be_bytes(b.get(at..at + 4)?.try_into().ok()?))
}

impl<'a> Tables<'a> {
    /// The table directory of a TrueType (`0x00010000`) font.
    fn read(data: &'a [u8]) -> Option<Self> {
        if u32_at(data, 0)? != 0x0001_0000 {
            return None;
        }
        let count = usize::from(u16_at(data, 4)?);
        let mut tables = BTreeMap::new();
        for k in 0..count {
            let record = 12 + 16 * k;
            let tag: [u8; 4] = data.get(record..record + 4)?.try_into().ok()?;
            let offset = usize::try_from(u32_at(data, record + 8)?).ok()?;
            let length = usize::try_from(u32_at(data, record + 12)?).ok()?;
            tables.insert(tag, data.get(offset..offset.checked_add(length)?)?);
        }
        Some(Self { tables })
    }

    fn get(&self, tag: &[u8; 4]) -> Option<&'a [u8]> {
        self.tables.get(tag).copied()
    }

    /// The bytes of glyph `g` in `glyf` (empty for a glyph without outline).
    fn glyph(&self, g: u16) -> Option<&'a [u8]> {
        let (loca, glyf) = (self.get(b"loca")?, self.get(b"glyf")?);
        let long = u16_at(self.get(b"head")?, 50)? == 1;
        let g = usize::from(g);
        let (start, end) = if long {
            (u32_at(loca, 4 * g)? as usize, u32_at(loca, 4 * g + 4)? as usize)
        } else {
            (2 * usize::from(u16_at(loca, 2 * g)?), 2 * usize::from(u16_at(loca, 2 * g + 2)?))
        };
        glyf.get(start..end)
    }

    /// The advance width and left side bearing of glyph `g` (`hmtx`: after the last full
    /// metric, glyphs share its advance and list only their bearing).
    fn metric(&self, g: u16) -> Option<(u16, u16)> {
        let hmtx = self.get(b"hmtx")?;
        let full = usize::from(u16_at(self.get(b"hhea")?, 34)?);
        let g = usize::from(g);
        if g < full {
            Some((u16_at(hmtx, 4 * g)?, u16_at(hmtx, 4 * g + 2)?))
        } else {
            Some((u16_at(hmtx, 4 * (full - 1))?, u16_at(hmtx, 4 * full + 2 * (g - full))?))
        }
    }
}

/// The components of a composite glyph: each component index with its byte position in the
/// glyph (to rewrite it); empty for a simple glyph.
fn components(glyph: &[u8]) -> Vec<(u16, usize)> {
    let mut out = Vec::new();
    let Some(contours) = u16_at(glyph, 0) else { return out };
    // A negative number of contours marks a composite.
    if contours & 0x8000 == 0 {
        return out;
    }
    let mut at = 10;
    while let (Some(flags), Some(index)) = (u16_at(glyph, at), u16_at(glyph, at + 2)) {
        out.push((index, at + 2));
        at += 4 + if flags & ARG_1_AND_2_ARE_WORDS != 0 { 4 } else { 2 };
        at += if flags & WE_HAVE_A_SCALE != 0 {
            2
        } else if flags & WE_HAVE_AN_X_AND_Y_SCALE != 0 {
            4
        } else if flags & WE_HAVE_A_TWO_BY_TWO != 0 {
            8
        } else {
            0
        };
        if flags & MORE_COMPONENTS == 0 {
            break;
        }
    }
    out
}

/// The font `data` cut down to the characters `chars` and the glyph `glyph_of` gives each (0:
/// the font lacks it, left out); `None` when `data` is not a TrueType font this reads.
#[must_use]
pub fn subset(
    data: &[u8],
    chars: impl IntoIterator<Item = char>,
    glyph_of: impl Fn(char) -> u16,
) -> Option<Vec<u8>> {
    let font = Tables::read(data)?;
    let mapped: BTreeMap<char, u16> =
        chars.into_iter().map(|c| (c, glyph_of(c))).filter(|(_, g)| *g != 0).collect();
    // The kept glyphs, old ids in new order: 0, the characters', then their components.
    let mut kept: Vec<u16> = vec![0];
    let mut queue: Vec<(u16, usize)> = mapped.values().map(|g| (*g, 0)).collect();
    while let Some((g, depth)) = queue.pop() {
        if kept.contains(&g) {
            continue;
        }
        kept.push(g);
        if depth < MAX_COMPOSITE_DEPTH {
            queue.extend(components(font.glyph(g)?).into_iter().map(|(c, _)| (c, depth + 1)));
        }
    }
    kept[1..].sort_unstable();
    let new_id = |old: u16| kept.iter().position(|k| *k == old).and_then(|p| u16::try_from(p).ok());
    let count = u16::try_from(kept.len()).ok()?;

    let (mut glyf, mut loca, mut hmtx) = (Vec::new(), Vec::new(), Vec::new());
    for &old in &kept {
        loca.extend(u32::try_from(glyf.len()).ok()?.to_be_bytes());
        let mut bytes = font.glyph(old)?.to_vec();
        for (component, at) in components(&bytes.clone()) {
            bytes[at..at + 2].copy_from_slice(&new_id(component)?.to_be_bytes());
        }
        glyf.extend(&bytes);
        glyf.resize(glyf.len().next_multiple_of(4), 0);
        let (advance, bearing) = font.metric(old)?;
        hmtx.extend(advance.to_be_bytes());
        hmtx.extend(bearing.to_be_bytes());
    }
    loca.extend(u32::try_from(glyf.len()).ok()?.to_be_bytes());

    let mut head = font.get(b"head")?.to_vec();
    head.get_mut(8..12)?.copy_from_slice(&[0; 4]);
    head.get_mut(50..52)?.copy_from_slice(&1u16.to_be_bytes());
    let mut hhea = font.get(b"hhea")?.to_vec();
    hhea.get_mut(34..36)?.copy_from_slice(&count.to_be_bytes());
    let mut maxp = font.get(b"maxp")?.to_vec();
    maxp.get_mut(4..6)?.copy_from_slice(&count.to_be_bytes());
    let mut post = font.get(b"post")?.get(..32)?.to_vec();
    post[..4].copy_from_slice(&0x0003_0000u32.to_be_bytes());

    // cmap: one (3, 10) subtable of format 12, a group per character.
    let groups = u32::try_from(mapped.len()).ok()?;
    let mut cmap = Vec::new();
    cmap.extend(0u16.to_be_bytes());
    cmap.extend(1u16.to_be_bytes());
    cmap.extend(3u16.to_be_bytes());
    cmap.extend(10u16.to_be_bytes());
    cmap.extend(12u32.to_be_bytes());
    cmap.extend(12u16.to_be_bytes());
    cmap.extend(0u16.to_be_bytes());
    cmap.extend((16 + 12 * groups).to_be_bytes());
    cmap.extend(0u32.to_be_bytes());
    cmap.extend(groups.to_be_bytes());
    for (c, g) in &mapped {
        let code = u32::from(*c);
        cmap.extend(code.to_be_bytes());
        cmap.extend(code.to_be_bytes());
        cmap.extend(u32::from(new_id(*g)?).to_be_bytes());
    }

    let tables: BTreeMap<[u8; 4], Vec<u8>> = [
        (*b"OS/2", font.get(b"OS/2")?.to_vec()),
        (*b"cmap", cmap),
        (*b"glyf", glyf),
        (*b"head", head),
        (*b"hhea", hhea),
        (*b"hmtx", hmtx),
        (*b"loca", loca),
        (*b"maxp", maxp),
        (*b"name", font.get(b"name")?.to_vec()),
        (*b"post", post),
    ]
    .into_iter()
    .collect();
    Some(assemble(&tables))
}

/// The sum of a table's big-endian u32 words, zero-padded to 4 bytes (OpenType's checksum).
fn checksum(bytes: &[u8]) -> u32 {
    bytes.chunks(4).fold(0u32, |sum, chunk| {
        let mut word = [0u8; 4];
        word[..chunk.len()].copy_from_slice(chunk);
        sum.wrapping_add(u32::from_be_bytes(word))
    })
}

/// A font file of `tables` (sorted by tag): the offset table, the directory, the tables each
/// padded to 4 bytes, and `head.checkSumAdjustment`.
fn assemble(tables: &BTreeMap<[u8; 4], Vec<u8>>) -> Vec<u8> {
    let count = u16::try_from(tables.len()).unwrap_or(u16::MAX);
    // searchRange: 16 × the largest power of two ≤ count; entrySelector: its log2.
    let selector = u16::try_from(count.max(1).ilog2()).unwrap_or(0);
    let range = 16 * (1u16 << selector);
    let mut out = Vec::new();
    out.extend(0x0001_0000u32.to_be_bytes());
    out.extend(count.to_be_bytes());
    out.extend(range.to_be_bytes());
    out.extend(selector.to_be_bytes());
    out.extend((count * 16 - range).to_be_bytes());
    let mut offset = 12 + 16 * tables.len();
    let mut head_at = None;
    for (tag, bytes) in tables {
        out.extend(tag);
        out.extend(checksum(bytes).to_be_bytes());
        out.extend(u32::try_from(offset).unwrap_or(u32::MAX).to_be_bytes());
        out.extend(u32::try_from(bytes.len()).unwrap_or(u32::MAX).to_be_bytes());
        if tag == b"head" {
            head_at = Some(offset);
        }
        offset += bytes.len().next_multiple_of(4);
    }
    for bytes in tables.values() {
        out.extend(bytes);
        out.resize(out.len().next_multiple_of(4), 0);
    }
    if let Some(at) = head_at {
        let adjustment = CHECKSUM_MAGIC.wrapping_sub(checksum(&out));
        out[at + 8..at + 12].copy_from_slice(&adjustment.to_be_bytes());
    }
    out
}

/// `bytes` in base64 (RFC 4648, with padding): a font in a `data:` URL, the module in a page.
#[must_use]
pub fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [chunk[0], chunk.get(1).copied().unwrap_or(0), chunk.get(2).copied().unwrap_or(0)];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(char::from(ALPHABET[((n >> (18 - 6 * k)) & 63) as usize]));
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::text::{font, math_font, Weight};
    use ab_glyph::{Font, FontRef};

    #[test]
    fn base64_as_the_rfc_s_examples() {
        // RFC 4648 §10.
        for (plain, coded) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(plain.as_bytes()), coded);
        }
        assert_eq!(base64(&[0xff, 0xfe, 0x00]), "//4A");
    }

    #[test]
    #[allow(clippy::float_cmp)] // advances read from the same font units must be the very same
    fn a_subset_draws_its_characters_as_the_whole_font_does_and_is_small() {
        let whole = font(Weight::Regular);
        let text = "Adâncimea maximă: ș ț Î θ₁ T₂ (0.392, 1.04)";
        let cut = subset(crate::text::regular_ttf(), text.chars(), |c| whole.glyph_id(c).0).unwrap();
        let part = FontRef::try_from_slice(&cut).unwrap();
        assert!(cut.len() < crate::text::regular_ttf().len() / 5, "{} bytes", cut.len());
        assert_eq!(checksum(&cut), CHECKSUM_MAGIC);
        for c in text.chars() {
            let (a, b) = (whole.glyph_id(c), part.glyph_id(c));
            assert_ne!(b.0, 0, "{c:?} lost");
            assert_eq!(whole.h_advance_unscaled(a), part.h_advance_unscaled(b), "{c:?}");
            // The same outline: as many curves, the same bounds (composites through their
            // renumbered components).
            let (oa, ob) = (whole.outline(a), part.outline(b));
            assert_eq!(oa.as_ref().map(|o| o.curves.len()), ob.as_ref().map(|o| o.curves.len()), "{c:?}");
            assert_eq!(oa.map(|o| o.bounds), ob.map(|o| o.bounds), "{c:?}");
        }
        // A character not asked for is not there.
        assert_eq!(part.glyph_id('Q').0, 0);
        // The math face subsets alike.
        let math = math_font();
        let cut = subset(crate::text::math_ttf(), ['→', '≤'], |c| math.glyph_id(c).0).unwrap();
        assert_ne!(FontRef::try_from_slice(&cut).unwrap().glyph_id('→').0, 0);
    }

    #[test]
    fn what_is_not_a_truetype_font_is_none() {
        assert!(subset(b"not a font", "a".chars(), |_| 1).is_none());
        assert!(subset(&[], "a".chars(), |_| 1).is_none());
    }
}

//! The two languages the tool speaks — the lecture's Romanian and English — and a text given in
//! both. Below everything that words something: a scene's object names, the narration, the
//! figures' labels and the lessons all take their [`Lang`] from here.

/// The language of the narration, the figures and the pages.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lang {
    /// English.
    En,
    /// Romanian, with diacritics.
    Ro,
}

/// The languages' codes, the fields of a [`Both`] written as JSON (`{"en": …, "ro": …}`).
pub const CODES: &[&str] = &["en", "ro"];

impl Lang {
    /// The language's code, as `lang` attributes and the JSON keys of a [`Both`] write it.
    #[must_use]
    pub const fn code(self) -> &'static str {
        match self {
            Self::En => "en",
            Self::Ro => "ro",
        }
    }
}

/// A text in both languages.
#[derive(Clone, Debug, PartialEq, Eq, Default)]
pub struct Both {
    /// English.
    pub en: String,
    /// Romanian.
    pub ro: String,
}

impl Both {
    /// The same text in every language (a name written as one string).
    #[must_use]
    pub fn same(text: &str) -> Self {
        Self { en: text.to_owned(), ro: text.to_owned() }
    }

    /// The text in `lang`.
    #[must_use]
    pub fn get(&self, lang: Lang) -> &str {
        match lang {
            Lang::En => &self.en,
            Lang::Ro => &self.ro,
        }
    }
}

//! `named_enum!`: the enums of codes (reasons, events, statuses, pairs) written once, with
//! their table of every variant and their printed names.

/// Declares a `pub enum` whose discriminants are 0, 1, 2, … in declaration order, with
/// `ALL` (every variant, indexed by discriminant; checked at compile time) and, when every
/// variant is followed by `=> "name"`, `name(self)`, the name the Python layer prints.
macro_rules! named_enum {
    (
        $(#[$meta:meta])*
        pub enum $name:ident {
            $($(#[$vmeta:meta])* $variant:ident = $code:literal => $text:literal,)+
        }
    ) => {
        named_enum! { $(#[$meta])* pub enum $name { $($(#[$vmeta])* $variant = $code,)+ } }

        impl $name {
            /// The name the Python layer prints.
            pub fn name(self) -> &'static str {
                match self {
                    $($name::$variant => $text,)+
                }
            }
        }
    };
    (
        $(#[$meta:meta])*
        pub enum $name:ident {
            $($(#[$vmeta:meta])* $variant:ident = $code:literal,)+
        }
    ) => {
        $(#[$meta])*
        pub enum $name {
            $($(#[$vmeta])* $variant = $code,)+
        }

        impl $name {
            /// Every variant, indexed by discriminant.
            pub const ALL: [$name; [$($code),+].len()] = [$($name::$variant),+];
        }

        // ALL[i] has discriminant i.
        const _: () = {
            let mut i = 0;
            while i < $name::ALL.len() {
                assert!($name::ALL[i] as usize == i);
                i += 1;
            }
        };
    };
}
